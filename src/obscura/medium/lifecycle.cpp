#include "obscura/medium/lifecycle.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

namespace {

// Times within this relative distance of a keyframe's time are that keyframe:
// the loop's fmod leaves rounding of a few ulps of u, and a state that should
// be exactly a keyframe (weight 0) must not come out as weight 1e-16 of the
// next one. 1e-12 of a 1000 s time is a nanosecond.
constexpr double kSnap = 1e-12;

double snap_tolerance(double u, double s) {
  return kSnap * std::max({1.0, std::abs(u), std::abs(s)});
}

}  // namespace

std::string to_string(CloudPhase phase) {
  switch (phase) {
    case CloudPhase::kAbsent:
      return "absent";
    case CloudPhase::kInitialisation:
      return "initialisation";
    case CloudPhase::kEvolution:
      return "evolution";
    case CloudPhase::kExtinction:
      return "extinction";
    case CloudPhase::kExtinct:
      return "extinct";
  }
  return "unknown";
}

bool LifecycleState::present() const {
  return phase == CloudPhase::kInitialisation || phase == CloudPhase::kEvolution ||
         phase == CloudPhase::kExtinction;
}

Lifecycle::Lifecycle(std::vector<double> keyframe_times_s, LifecycleSpec spec,
                     const std::string& source)
    : times_(std::move(keyframe_times_s)), spec_(spec) {
  const int n = static_cast<int>(times_.size());
  if (n < 1) throw InputError(source, "keyframes", "a cloud needs at least one keyframe");
  for (int k = 0; k < n; ++k) {
    const std::string field = fmt::format("keyframes/{}/time", k);
    if (!std::isfinite(times_[k]) || times_[k] < 0)
      throw InputError(source, field,
                       fmt::format("must be a finite time >= 0 s, found {}", times_[k]));
    if (k > 0 && !(times_[k] > times_[k - 1]))
      throw InputError(source, field,
                       fmt::format("keyframe times must increase strictly: {} s follows {} s",
                                   times_[k], times_[k - 1]));
  }
  const auto index_in_range = [&](int value, const char* name) {
    if (value < 0 || value > n - 1)
      throw InputError(
          source, std::string("lifecycle/") + name,
          fmt::format("keyframe index {} out of range [0, {}] ({} keyframes)", value, n - 1, n));
  };
  index_in_range(spec_.init_end, "init_end");
  index_in_range(spec_.loop_start, "loop_start");
  index_in_range(spec_.loop_end, "loop_end");
  if (spec_.loop_start < spec_.init_end)
    throw InputError(
        source, "lifecycle/loop_start",
        fmt::format("must be >= init_end ({}), found {}", spec_.init_end, spec_.loop_start));
  if (spec_.loop_end < spec_.loop_start)
    throw InputError(
        source, "lifecycle/loop_end",
        fmt::format("must be >= loop_start ({}), found {}", spec_.loop_start, spec_.loop_end));
  if (spec_.extinction_start <= spec_.loop_end || spec_.extinction_start > n - 1)
    throw InputError(source, "lifecycle/extinction_start",
                     fmt::format("must lie in [loop_end + 1, n − 1] = [{}, {}] (extinction needs "
                                 "at least one keyframe after the loop), found {}",
                                 spec_.loop_end + 1, n - 1, spec_.extinction_start));
  if (!std::isfinite(spec_.loop_wrap_s) || spec_.loop_wrap_s < 0)
    throw InputError(source, "lifecycle/loop_wrap",
                     fmt::format("must be a finite duration >= 0 s, found {}", spec_.loop_wrap_s));
  // A zero-length wrap would jump from K[b] to K[a]: not an interpolation.
  if (spec_.loop_start < spec_.loop_end && !(spec_.loop_wrap_s > 0))
    throw InputError(source, "lifecycle/loop_wrap",
                     "must be > 0 s when the loop has more than one keyframe (the wrap from "
                     "loop_end back to loop_start is interpolated over it)");
}

double Lifecycle::loop_period_s() const {
  return times_[spec_.loop_end] - times_[spec_.loop_start] + spec_.loop_wrap_s;
}

// Keyframes (k, k+1) with τ_k <= s < τ_{k+1} among first..last, where s is a
// time on the keyframes' own clock reached at local time u. Needs
// τ_first <= s < τ_last.
Lifecycle::Interval Lifecycle::bracket(int first, int last, double s, double u) const {
  const auto begin = times_.begin() + first, end = times_.begin() + last + 1;
  int k = static_cast<int>(std::upper_bound(begin, end, s) - times_.begin()) - 1;
  k = std::clamp(k, first, last - 1);
  const double tol = snap_tolerance(u, s);
  double offset = s - times_[k];  // seconds since keyframe k
  if (times_[k + 1] - s <= tol && k + 1 < last) {
    ++k;
    offset = 0;
  } else if (offset <= tol) {
    offset = 0;
  }
  const double span = times_[k + 1] - times_[k];
  Interval r;
  r.state.keyframe0 = k;
  r.state.keyframe1 = k + 1;
  r.state.weight = offset == 0 ? 0.0 : offset / span;
  r.start_s = u - offset;
  r.end_s = r.start_s + span;
  r.target = k + 1;
  return r;
}

Lifecycle::Interval Lifecycle::running(double u) const {
  const int e = spec_.init_end, a = spec_.loop_start, b = spec_.loop_end;
  const auto hold = [u](int k) {
    Interval r;
    r.state.keyframe0 = r.state.keyframe1 = k;
    r.start_s = r.end_s = u;
    r.target = k;
    return r;
  };
  Interval r;
  if (u < times_[0]) {
    r = hold(0);  // activated before the first keyframe's time: show keyframe 0
  } else if (u < times_[a]) {
    // Initialisation, then (if init_end < loop_start) the keyframes leading
    // into the loop, all played once at their own times.
    r = bracket(0, a, u, u);
  } else if (a == b || !(loop_period_s() > 0)) {
    r = hold(a);  // a one-keyframe loop is a constant state
  } else {
    const double period = loop_period_s();
    const double length = times_[b] - times_[a];  // the loop's keyframes, without the wrap
    double v = std::fmod(u - times_[a], period);
    const double tol = snap_tolerance(u, v);
    if (period - v <= tol) v = 0;
    if (v < length - tol) {
      r = bracket(a, b, times_[a] + v, u);
    } else {
      // The wrap K[b] → K[a], over loop_wrap_s; exactly K[b] at its start.
      const double into = v < length + tol ? 0.0 : v - length;
      r.state.keyframe0 = b;
      r.state.keyframe1 = a;
      r.state.weight = into == 0 ? 0.0 : into / spec_.loop_wrap_s;
      r.start_s = u - into;
      r.end_s = r.start_s + spec_.loop_wrap_s;
      r.target = a;
    }
  }
  r.state.phase = u < times_[e] ? CloudPhase::kInitialisation : CloudPhase::kEvolution;
  r.state.local_time_s = u;
  return r;
}

// The state at local time u >= u_d of a cloud deactivated at local time u_d > 0.
LifecycleState Lifecycle::extinction(double u, double u_d) const {
  const int x = spec_.extinction_start, last = static_cast<int>(times_.size()) - 1;
  const Interval in_progress = running(u_d);
  // Deactivated exactly at a keyframe (weight 0) or during a hold: the cloud
  // has arrived at that keyframe and heads for K[x] at once. Otherwise the
  // interval in progress is completed first.
  const bool arrived = in_progress.state.weight == 0.0;
  const int q = arrived ? in_progress.state.keyframe0 : in_progress.target;
  const double u_q = arrived ? u_d : in_progress.end_s;

  LifecycleState s;
  s.phase = CloudPhase::kExtinction;
  s.local_time_s = u;
  if (u < u_q) {
    s.keyframe0 = in_progress.state.keyframe0;
    s.keyframe1 = in_progress.state.keyframe1;
    s.weight = (u - in_progress.start_s) / (in_progress.end_s - in_progress.start_s);
    return s;
  }
  // K[q] → K[x] over the time the keyframes take from the loop's end to x.
  const double d = times_[x] - times_[spec_.loop_end];
  const double since = u - u_q;
  if (since < d) {
    s.keyframe0 = q;
    s.keyframe1 = x;
    s.weight = since / d;
    return s;
  }
  // Keyframes x..n−1 at their own spacing, K[x] reached at u_q + d; the cloud
  // is gone the moment the last keyframe would be reached.
  const double r = std::max(times_[x], times_[x] + (since - d));
  if (x == last || r >= times_[last]) {
    s.phase = CloudPhase::kExtinct;
    return s;
  }
  const Interval tail = bracket(x, last, r, u);
  s.keyframe0 = tail.state.keyframe0;
  s.keyframe1 = tail.state.keyframe1;
  s.weight = tail.state.weight;
  return s;
}

LifecycleState Lifecycle::at(double t, double activation_s,
                             std::optional<double> deactivation_s) const {
  if (std::isnan(t) || std::isnan(activation_s) || (deactivation_s && std::isnan(*deactivation_s)))
    throw Error("Lifecycle::at: time is NaN");
  const double u = t - activation_s;
  LifecycleState s;
  s.local_time_s = u;
  if (u < 0) return s;  // not yet activated
  if (deactivation_s) {
    if (*deactivation_s <= activation_s) {
      // Deactivated before it was activated: the cloud never appears.
      s.phase = CloudPhase::kExtinct;
      return s;
    }
    const double u_d = *deactivation_s - activation_s;  // +inf: never
    if (u >= u_d) return extinction(u, u_d);
  }
  return running(u).state;
}

}  // namespace obscura
