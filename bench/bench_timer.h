#pragma once
// The one timer every benchmark uses: wall time since a steady-clock instant.
#include <chrono>

namespace obscura::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace obscura::bench
