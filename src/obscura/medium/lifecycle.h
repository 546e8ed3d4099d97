#pragma once
// The life of a time-varying cloud as a map from scene time to two keyframes
// and a weight (docs/conventions.md §4): an initialisation phase played once from the
// activation, an evolution phase that loops, and, after the deactivation, an
// extinction phase after which the cloud is gone for good. Pure time logic: no
// grids are touched here (docs/time-varying-clouds.md, "Lifecycle").
#include <optional>
#include <string>
#include <vector>

namespace obscura {

enum class CloudPhase { kAbsent, kInitialisation, kEvolution, kExtinction, kExtinct };

// "absent", "initialisation", "evolution", "extinction", "extinct".
std::string to_string(CloudPhase phase);

// Keyframe indexes (0-based) that delimit the phases, and the duration of the
// loop's jump back from its last keyframe to its first.
struct LifecycleSpec {
  int init_end = 0;          // e: last keyframe of the initialisation phase
  int loop_start = 0;        // a: first keyframe of the loop
  int loop_end = 0;          // b: last keyframe of the loop
  double loop_wrap_s = 0;    // w: seconds to interpolate K[b] → K[a] when looping
  int extinction_start = 0;  // x: first keyframe of the extinction phase (x > b)
};

// A cloud's state at one time: state = (1 − weight)·K[keyframe0] + weight·K[keyframe1].
// At a keyframe's exact time weight is exactly 0 and keyframe0 is that keyframe.
struct LifecycleState {
  CloudPhase phase = CloudPhase::kAbsent;
  int keyframe0 = -1, keyframe1 = -1;  // -1 while absent or extinct
  double weight = 0;                   // in [0, 1)
  double local_time_s = 0;             // t − activation, s
  // True in the initialisation, evolution and extinction phases.
  bool present() const;
};

class Lifecycle {
 public:
  // keyframe_times_s: each keyframe's time after the activation, s; strictly
  // increasing, finite, >= 0. Throws InputError(source, field, ...) naming the
  // field ("lifecycle/loop_end", "keyframes/3/time", ...) when the spec is
  // inconsistent: needs 0 <= init_end <= loop_start <= loop_end <
  // extinction_start <= n − 1, loop_wrap_s finite and >= 0, and > 0 when the
  // loop has more than one keyframe.
  Lifecycle(std::vector<double> keyframe_times_s, LifecycleSpec spec,
            const std::string& source = "");

  // State at scene time t (s) of a cloud activated at activation_s and
  // deactivated at deactivation_s (nullopt or +inf: never). Times must not be NaN.
  LifecycleState at(double t, double activation_s, std::optional<double> deactivation_s) const;

  const std::vector<double>& keyframe_times_s() const { return times_; }
  const LifecycleSpec& spec() const { return spec_; }
  // τ[loop_end] − τ[loop_start] + loop_wrap_s, s.
  double loop_period_s() const;

 private:
  // The undeactivated state at local time u >= 0, with the interpolation
  // interval in progress: it runs from local time start_s to end_s, at which
  // keyframe `target` is reached (start_s == end_s for a held keyframe).
  struct Interval {
    LifecycleState state;
    double start_s = 0, end_s = 0;
    int target = 0;
  };
  Interval running(double u) const;
  Interval bracket(int first, int last, double s, double u) const;
  LifecycleState extinction(double u, double u_d) const;

  std::vector<double> times_;
  LifecycleSpec spec_;
};

}  // namespace obscura
