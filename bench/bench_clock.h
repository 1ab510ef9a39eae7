// Clock helpers shared by the benches (never by the tests): a monotonic clock in seconds, the
// calling thread's CPU time in seconds, and the machine's load average, printed beside every
// timing so a reader can judge it.
#pragma once

#include <chrono>
#include <ctime>
#include <fstream>
#include <string>

namespace rondo::bench {

inline double steady_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

// CPU time of the calling thread: what a piece of work costs it, whatever else the machine runs.
inline double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace rondo::bench
