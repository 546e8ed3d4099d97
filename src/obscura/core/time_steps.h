#pragma once
// Evenly spaced times, as `--time A:B:STEP`, a preparation's and a study's
// "times_s": {"start", "end", "step"} give them: start, start + step, … up to
// end inclusive, an end within 1e-9 of a step counting as reached. One rule
// for every caller, so a study's frames are the frames `render --time`
// gives for the same numbers.
#include <cmath>
#include <cstddef>
#include <vector>

namespace obscura {

// How many times; needs finite start <= end and step > 0 (callers check, and
// refuse counts too large for them before asking for the list).
inline double time_step_count(double start_s, double end_s, double step_s) {
  return std::floor((end_s - start_s) / step_s + 1e-9) + 1.0;
}

inline std::vector<double> time_steps(double start_s, double end_s, double step_s) {
  const auto n = static_cast<std::size_t>(time_step_count(start_s, end_s, step_s));
  std::vector<double> times;
  times.reserve(n);
  for (std::size_t k = 0; k < n; ++k) times.push_back(start_s + static_cast<double>(k) * step_s);
  return times;
}

}  // namespace obscura
