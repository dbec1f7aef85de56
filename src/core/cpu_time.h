#pragma once

#include <time.h>

#include <ctime>

// CPU clocks for the work counters the benchmarks report (unit tests never assert them).
namespace semchain {

// CPU seconds of the whole process (every thread), as std::clock counts them.
inline double ProcessCpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// CPU seconds of the calling thread only: a method's own work while other threads run.
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace semchain
