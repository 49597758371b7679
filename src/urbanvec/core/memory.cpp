#include "urbanvec/core/memory.hpp"

#include <algorithm>
#include <atomic>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace urbanvec {

namespace {

std::atomic<long> earlierPeakKb{-1};  ///< the highest mark a reset cleared

long statusKb(const char* key) {
  std::ifstream f("/proc/self/status");
  const std::string prefix = key;
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(prefix, 0) == 0) return std::stol(line.substr(prefix.size()));
  return -1;
}

}  // namespace

long peakMemoryKb() {
  return statusKb("VmHWM:");
}

long residentMemoryKb() {
  return statusKb("VmRSS:");
}

void resetPeakMemory() {
  const long peak = peakMemoryKb();
  long seen = earlierPeakKb.load();
  while (peak > seen && !earlierPeakKb.compare_exchange_weak(seen, peak)) {
  }
  std::ofstream f("/proc/self/clear_refs");
  if (f) f << "5";
}

long processPeakMemoryKb() {
  return std::max(earlierPeakKb.load(), peakMemoryKb());
}

void releaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace urbanvec
