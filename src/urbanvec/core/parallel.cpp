#include "urbanvec/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace urbanvec {

std::size_t workerCount(int threads) {
  return threads > 0 ? static_cast<std::size_t>(threads)
                     : std::max<std::size_t>(1, std::thread::hardware_concurrency());
}

void runParallel(std::size_t workers, std::size_t n,
                 const std::function<void(std::size_t, std::size_t)>& body,
                 const std::function<void(std::size_t)>& tick) {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::exception_ptr failure;
  std::exception_ptr cancelled;
  std::size_t failureIndex = std::numeric_limits<std::size_t>::max();
  std::size_t reported = 0;
  auto work = [&](std::size_t worker, bool caller) {
    while (!stop) {
      const std::size_t i = next++;
      if (i >= n) break;
      try {
        body(i, worker);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (i < failureIndex) {  // the lowest failing item, whatever the scheduling
          failureIndex = i;
          failure = std::current_exception();
        }
        stop = true;
      }
      ++finished;
      if (caller && tick && !stop) {
        const std::size_t now = finished;
        try {
          tick(now - reported);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex);
          cancelled = std::current_exception();
          stop = true;
        }
        reported = now;
      }
    }
  };
  std::vector<std::thread> pool;
  const std::size_t threads = std::min(std::max<std::size_t>(1, workers), n);
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work, t, false);
  } catch (...) {
    stop = true;
    for (std::thread& t : pool) t.join();
    throw;
  }
  if (n > 0) work(0, true);
  for (std::thread& t : pool) t.join();
  if (cancelled) std::rethrow_exception(cancelled);
  if (failure) std::rethrow_exception(failure);
  if (tick && finished > reported) tick(finished - reported);
}

void runChunks(std::size_t workers, std::size_t n, std::size_t chunk,
               const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  chunk = std::max<std::size_t>(1, chunk);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  if (workers <= 1 || chunks <= 1) {
    if (n > 0) body(0, n, 0);
    return;
  }
  runParallel(workers, chunks, [&](std::size_t c, std::size_t worker) {
    body(c * chunk, std::min(n, (c + 1) * chunk), worker);
  });
}

}  // namespace urbanvec
