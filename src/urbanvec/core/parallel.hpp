// Worker threads for independent per-item loops (issue 21): one helper for every stage that runs on
// -threads, so each stage's result can be made not to depend on the thread count by writing only
// item i's own slot in body(i).
#pragma once

#include <cstddef>
#include <functional>

namespace urbanvec {

/// The number of workers for a -threads value: `threads` when positive, else all cores (at least 1).
std::size_t workerCount(int threads);

/// Runs body(i, worker) for every i in [0, n) on `workers` threads (the calling thread is worker 0,
/// never more threads than items). Items are claimed in increasing order. `tick`, when set, runs on the
/// calling thread only, with the number of items finished since its previous call (for progress; it may
/// throw Cancelled). The exception of the lowest failing item is rethrown once every worker has stopped.
void runParallel(std::size_t workers, std::size_t n,
                 const std::function<void(std::size_t, std::size_t)>& body,
                 const std::function<void(std::size_t)>& tick = {});

/// runParallel over the chunks [begin, end) of [0, n), `chunk` items each (the last one shorter), for
/// loops whose items are too cheap for one claim each: body(begin, end, worker).
void runChunks(std::size_t workers, std::size_t n, std::size_t chunk,
               const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

}  // namespace urbanvec
