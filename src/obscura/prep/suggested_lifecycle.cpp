#include "obscura/prep/suggested_lifecycle.h"

#include <algorithm>

#include "obscura/core/error.h"

namespace obscura {

LifecycleSpec suggest_lifecycle(const std::vector<double>& times,
                                std::optional<double> burn_end_s) {
  const int n = static_cast<int>(times.size());
  if (n < 2)
    throw InputError(
        "", "times",
        "a lifecycle needs at least two keyframes (one after the loop for the extinction)");
  int e = 0;
  if (burn_end_s)
    for (int k = 0; k < n; ++k)
      if (times[k] <= *burn_end_s) e = k;
  e = std::min(e, n - 2);  // leave at least one keyframe for the extinction
  LifecycleSpec s;
  s.init_end = e;
  s.loop_start = e;
  s.loop_end = e + (n - 1 - e) / 2;
  if (s.loop_end >= n - 1) s.loop_end = n - 2;
  s.extinction_start = s.loop_end + 1;
  // Wrap K_b → K_a over one keyframe interval (required > 0 when a < b).
  s.loop_wrap_s = s.loop_end > s.loop_start ? (times[s.loop_end] - times[s.loop_end - 1]) : 0.0;
  return s;
}

}  // namespace obscura
