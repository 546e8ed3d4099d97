// The cloud lifecycle against hand-computed (keyframes, weight) at chosen
// times: every phase transition of the example manifest of
// docs/time-varying-clouds.md, the deactivation rules and their edge cases.
#include "obscura/medium/lifecycle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "obscura/core/error.h"

namespace obscura {
namespace {

using P = CloudPhase;

// The example: keyframes at 0, 1, …, 10 s; initialisation 0..3, loop 4..7
// with a 1 s wrap (period 4 s), extinction 8..10.
Lifecycle example() {
  std::vector<double> times;
  for (int k = 0; k <= 10; ++k) times.push_back(k);
  return Lifecycle(times, {3, 4, 7, 1.0, 8}, "example.json");
}

void expect_state(const LifecycleState& s, P phase, int k0, int k1, double weight) {
  EXPECT_EQ(s.phase, phase) << to_string(s.phase) << " at u = " << s.local_time_s;
  EXPECT_EQ(s.keyframe0, k0) << "at u = " << s.local_time_s;
  EXPECT_EQ(s.keyframe1, k1) << "at u = " << s.local_time_s;
  EXPECT_EQ(s.weight, weight) << "at u = " << s.local_time_s;  // exact: these are dyadic
}

constexpr std::optional<double> kNever = std::nullopt;

TEST(Lifecycle, PhaseNames) {
  EXPECT_EQ(to_string(P::kAbsent), "absent");
  EXPECT_EQ(to_string(P::kInitialisation), "initialisation");
  EXPECT_EQ(to_string(P::kEvolution), "evolution");
  EXPECT_EQ(to_string(P::kExtinction), "extinction");
  EXPECT_EQ(to_string(P::kExtinct), "extinct");
  LifecycleState s;
  for (P p : {P::kInitialisation, P::kEvolution, P::kExtinction}) {
    s.phase = p;
    EXPECT_TRUE(s.present());
  }
  for (P p : {P::kAbsent, P::kExtinct}) {
    s.phase = p;
    EXPECT_FALSE(s.present());
  }
}

TEST(Lifecycle, ExampleWithoutDeactivation) {
  const Lifecycle l = example();
  EXPECT_EQ(l.loop_period_s(), 4.0);
  expect_state(l.at(-1, 0, kNever), P::kAbsent, -1, -1, 0);
  expect_state(l.at(-1e-9, 0, kNever), P::kAbsent, -1, -1, 0);
  expect_state(l.at(0, 0, kNever), P::kInitialisation, 0, 1, 0);
  expect_state(l.at(0.5, 0, kNever), P::kInitialisation, 0, 1, 0.5);
  expect_state(l.at(2.25, 0, kNever), P::kInitialisation, 2, 3, 0.25);
  // Initialisation ends at τ[init_end] = 3 s; 3 → 4 leads into the loop.
  expect_state(l.at(3, 0, kNever), P::kEvolution, 3, 4, 0);
  expect_state(l.at(3.5, 0, kNever), P::kEvolution, 3, 4, 0.5);
  expect_state(l.at(4, 0, kNever), P::kEvolution, 4, 5, 0);
  expect_state(l.at(6.5, 0, kNever), P::kEvolution, 6, 7, 0.5);
  // The wrap K7 → K4 over 1 s: exactly K7 at its start.
  expect_state(l.at(7, 0, kNever), P::kEvolution, 7, 4, 0);
  expect_state(l.at(7.25, 0, kNever), P::kEvolution, 7, 4, 0.25);
  // Second lap.
  expect_state(l.at(8, 0, kNever), P::kEvolution, 4, 5, 0);
  expect_state(l.at(9.5, 0, kNever), P::kEvolution, 5, 6, 0.5);
  expect_state(l.at(11.75, 0, kNever), P::kEvolution, 7, 4, 0.75);
  expect_state(l.at(4000 + 1.5, 0, kNever), P::kEvolution, 5, 6, 0.5);
}

TEST(Lifecycle, LocalTimeIsRelativeToActivation) {
  const Lifecycle l = example();
  const LifecycleState s = l.at(12.5, 10, kNever);
  EXPECT_EQ(s.local_time_s, 2.5);
  expect_state(s, P::kInitialisation, 2, 3, 0.5);
  EXPECT_EQ(l.at(9, 10, kNever).local_time_s, -1);
  expect_state(l.at(9, 10, kNever), P::kAbsent, -1, -1, 0);
}

TEST(Lifecycle, LoopIsPeriodic) {
  const Lifecycle l = example();
  const double period = l.loop_period_s();
  for (double u = 4; u < 8; u += 0.125) {
    for (int lap = 1; lap <= 3; ++lap) {
      const LifecycleState s = l.at(u, 0, kNever), t = l.at(u + lap * period, 0, kNever);
      EXPECT_EQ(s.keyframe0, t.keyframe0) << u;
      EXPECT_EQ(s.keyframe1, t.keyframe1) << u;
      EXPECT_EQ(s.weight, t.weight) << u;
      EXPECT_EQ(t.phase, P::kEvolution);
    }
  }
}

// Keyframe times that are not representable (k · 0.1 s): at a keyframe's time,
// however many laps later, the state is exactly that keyframe, weight 0.0.
TEST(Lifecycle, ExactKeyframeAtKeyframeTimesAfterManyLaps) {
  std::vector<double> times;
  for (int k = 0; k <= 10; ++k) times.push_back(0.1 * k);
  const Lifecycle l(times, {3, 4, 7, 0.1, 8});
  const double period = l.loop_period_s();
  for (int lap = 0; lap <= 200; ++lap) {
    for (int j = 4; j <= 6; ++j) {
      const LifecycleState s = l.at(times[j] + lap * period, 0, kNever);
      EXPECT_EQ(s.keyframe0, j) << "lap " << lap;
      EXPECT_EQ(s.weight, 0.0) << "lap " << lap << " keyframe " << j;
    }
    const LifecycleState end = l.at(times[7] + lap * period, 0, kNever);
    EXPECT_EQ(end.keyframe0, 7) << "lap " << lap;
    EXPECT_EQ(end.weight, 0.0) << "lap " << lap;
  }
  for (int j = 0; j <= 3; ++j) {
    const LifecycleState s = l.at(times[j], 0, kNever);
    EXPECT_EQ(s.keyframe0, j);
    EXPECT_EQ(s.weight, 0.0);
  }
}

TEST(Lifecycle, DeactivationDuringTheLoopCompletesTheIntervalThenGoesToExtinction) {
  const Lifecycle l = example();
  const std::optional<double> off = 5.5;  // mid-way K5 → K6: K6 reached at 6 s
  expect_state(l.at(5.25, 0, off), P::kEvolution, 5, 6, 0.25);
  expect_state(l.at(5.5, 0, off), P::kExtinction, 5, 6, 0.5);
  expect_state(l.at(5.75, 0, off), P::kExtinction, 5, 6, 0.75);
  // K6 → K8 over τ8 − τ7 = 1 s.
  expect_state(l.at(6, 0, off), P::kExtinction, 6, 8, 0);
  expect_state(l.at(6.5, 0, off), P::kExtinction, 6, 8, 0.5);
  // Then K8 … K10 at their own 1 s spacing, from 7 s.
  expect_state(l.at(7, 0, off), P::kExtinction, 8, 9, 0);
  expect_state(l.at(7.5, 0, off), P::kExtinction, 8, 9, 0.5);
  expect_state(l.at(8.5, 0, off), P::kExtinction, 9, 10, 0.5);
  // Gone the moment K10 would be reached, for good.
  expect_state(l.at(9, 0, off), P::kExtinct, -1, -1, 0);
  expect_state(l.at(1e6, 0, off), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, DeactivationDuringTheWrapCompletesTheWrap) {
  const Lifecycle l = example();
  const std::optional<double> off = 7.5;  // K7 → K4 half done: K4 reached at 8 s
  expect_state(l.at(7.75, 0, off), P::kExtinction, 7, 4, 0.75);
  expect_state(l.at(8, 0, off), P::kExtinction, 4, 8, 0);
  expect_state(l.at(8.5, 0, off), P::kExtinction, 4, 8, 0.5);
  expect_state(l.at(9, 0, off), P::kExtinction, 8, 9, 0);
  expect_state(l.at(11, 0, off), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, DeactivationDuringInitialisation) {
  const Lifecycle l = example();
  const std::optional<double> off = 1.25;  // K1 → K2 a quarter done
  expect_state(l.at(1, 0, off), P::kInitialisation, 1, 2, 0);
  expect_state(l.at(1.5, 0, off), P::kExtinction, 1, 2, 0.5);
  expect_state(l.at(2, 0, off), P::kExtinction, 2, 8, 0);
  expect_state(l.at(2.5, 0, off), P::kExtinction, 2, 8, 0.5);
  expect_state(l.at(3, 0, off), P::kExtinction, 8, 9, 0);
  expect_state(l.at(4.5, 0, off), P::kExtinction, 9, 10, 0.5);
  expect_state(l.at(5, 0, off), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, DeactivationExactlyAtAKeyframeHeadsStraightForExtinction) {
  const Lifecycle l = example();
  const std::optional<double> off = 5;  // exactly K5: it has arrived, q = 5
  expect_state(l.at(4.5, 0, off), P::kEvolution, 4, 5, 0.5);
  expect_state(l.at(5, 0, off), P::kExtinction, 5, 8, 0);
  expect_state(l.at(5.5, 0, off), P::kExtinction, 5, 8, 0.5);
  expect_state(l.at(6, 0, off), P::kExtinction, 8, 9, 0);
  expect_state(l.at(8, 0, off), P::kExtinct, -1, -1, 0);
  // At the wrap's start the cloud is exactly K7.
  expect_state(l.at(7.5, 0, 7.0), P::kExtinction, 7, 8, 0.5);
}

TEST(Lifecycle, DeactivationWithAnActivationOffset) {
  const Lifecycle l = example();
  // Activated at 100 s, deactivated at 105.5 s: the loop case shifted by 100 s.
  expect_state(l.at(106.5, 100, 105.5), P::kExtinction, 6, 8, 0.5);
  expect_state(l.at(109, 100, 105.5), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, DeactivationAtOrBeforeActivationMeansNeverPresent) {
  const Lifecycle l = example();
  for (double off : {1.0, 2.0}) {
    expect_state(l.at(1.5, 2, off), P::kAbsent, -1, -1, 0);
    expect_state(l.at(2, 2, off), P::kExtinct, -1, -1, 0);
    expect_state(l.at(7, 2, off), P::kExtinct, -1, -1, 0);
  }
}

TEST(Lifecycle, InfiniteDeactivationIsNever) {
  const Lifecycle l = example();
  expect_state(l.at(9.5, 0, std::numeric_limits<double>::infinity()), P::kEvolution, 5, 6, 0.5);
}

// a == b: the loop is one keyframe, held; extinction_start == n − 1: the cloud
// is gone as soon as it reaches K[x].
TEST(Lifecycle, SingleKeyframeLoopAndExtinctionAtTheLastKeyframe) {
  const Lifecycle l({0, 1, 2, 3}, {1, 2, 2, 0.0, 3});
  EXPECT_EQ(l.loop_period_s(), 0.0);
  expect_state(l.at(0.5, 0, kNever), P::kInitialisation, 0, 1, 0.5);
  expect_state(l.at(1.5, 0, kNever), P::kEvolution, 1, 2, 0.5);
  expect_state(l.at(2, 0, kNever), P::kEvolution, 2, 2, 0);
  expect_state(l.at(1000, 0, kNever), P::kEvolution, 2, 2, 0);
  // Deactivated while holding K2: K2 → K3 over τ3 − τ2 = 1 s, then gone.
  expect_state(l.at(50.5, 0, 50.0), P::kExtinction, 2, 3, 0.5);
  expect_state(l.at(51, 0, 50.0), P::kExtinct, -1, -1, 0);
  // A wrap duration on a one-keyframe loop changes nothing.
  const Lifecycle m({0, 1, 2, 3}, {1, 2, 2, 5.0, 3});
  expect_state(m.at(9, 0, kNever), P::kEvolution, 2, 2, 0);
}

TEST(Lifecycle, NoInitialisationPhase) {
  // e = a = 0: the loop K0..K2 starts at activation; period 4 + 2 = 6 s.
  const Lifecycle l({0, 2, 4, 6}, {0, 0, 2, 2.0, 3});
  EXPECT_EQ(l.loop_period_s(), 6.0);
  expect_state(l.at(0, 0, kNever), P::kEvolution, 0, 1, 0);
  expect_state(l.at(1, 0, kNever), P::kEvolution, 0, 1, 0.5);
  expect_state(l.at(4, 0, kNever), P::kEvolution, 2, 0, 0);
  expect_state(l.at(5, 0, kNever), P::kEvolution, 2, 0, 0.5);
  expect_state(l.at(6, 0, kNever), P::kEvolution, 0, 1, 0);
  expect_state(l.at(7, 0, kNever), P::kEvolution, 0, 1, 0.5);
  // Deactivated in the wrap at 5 s: K0 reached at 6 s, then K0 → K3 over 2 s.
  expect_state(l.at(7, 0, 5.0), P::kExtinction, 0, 3, 0.5);
  expect_state(l.at(8, 0, 5.0), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, FirstKeyframeAfterActivationIsHeld) {
  const Lifecycle l({1, 2, 3}, {0, 0, 1, 1.0, 2});
  expect_state(l.at(0, 0, kNever), P::kInitialisation, 0, 0, 0);
  expect_state(l.at(0.5, 0, kNever), P::kInitialisation, 0, 0, 0);
  expect_state(l.at(1.5, 0, kNever), P::kEvolution, 0, 1, 0.5);
  // Deactivated during the hold: K0 → K2 over τ2 − τ1 = 1 s from 0.5 s.
  expect_state(l.at(1, 0, 0.5), P::kExtinction, 0, 2, 0.5);
  expect_state(l.at(1.5, 0, 0.5), P::kExtinct, -1, -1, 0);
}

TEST(Lifecycle, KeyframesBetweenInitEndAndLoopStartArePlayedOnce) {
  // e = 1, a = 3: K1 → K2 → K3 at their own times, then the loop K3..K4.
  const Lifecycle l({0, 1, 2, 3, 4, 5}, {1, 3, 4, 1.0, 5});
  expect_state(l.at(0.5, 0, kNever), P::kInitialisation, 0, 1, 0.5);
  expect_state(l.at(1.5, 0, kNever), P::kEvolution, 1, 2, 0.5);
  expect_state(l.at(2.5, 0, kNever), P::kEvolution, 2, 3, 0.5);
  expect_state(l.at(4.5, 0, kNever), P::kEvolution, 4, 3, 0.5);
  expect_state(l.at(5.5, 0, kNever), P::kEvolution, 3, 4, 0.5);
}

// The interpolated state of scalar keyframes is continuous in time, across
// every phase boundary and for any deactivation time, until the cloud is gone.
TEST(Lifecycle, StateIsContinuousUntilExtinct) {
  const Lifecycle l = example();
  const std::vector<double> value = {3, -1, 4, 1, -5, 9, 2, -6, 5, 3, -5};
  const auto blend = [&](const LifecycleState& s) {
    return (1 - s.weight) * value[s.keyframe0] + s.weight * value[s.keyframe1];
  };
  const double step = 1e-3;
  for (std::optional<double> off :
       std::vector<std::optional<double>>{kNever, 0.3, 1.0, 3.7, 4.0, 6.2, 7.0, 7.3, 9.99, 21.5}) {
    LifecycleState prev = l.at(0, 0, off);
    for (double u = step; u < 40; u += step) {
      const LifecycleState s = l.at(u, 0, off);
      if (!s.present()) {
        EXPECT_EQ(s.phase, P::kExtinct);
        EXPECT_TRUE(off.has_value());
        break;
      }
      ASSERT_GE(s.weight, 0.0);
      ASSERT_LT(s.weight, 1.0);
      // Steepest keyframe difference 14 per second.
      ASSERT_LT(std::abs(blend(s) - blend(prev)), 14 * step * 1.001)
          << "u = " << u << " deactivation " << (off ? *off : -1);
      prev = s;
    }
  }
}

// The error names the field; returns its field ("" if no error).
std::string field_of(std::vector<double> times, LifecycleSpec spec) {
  try {
    Lifecycle l(std::move(times), spec, "cloud.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "cloud.json");
    return e.field();
  }
  return "";
}

TEST(Lifecycle, BadSpecsNameTheField) {
  const std::vector<double> t = {0, 1, 2, 3, 4};
  EXPECT_EQ(field_of(t, {1, 2, 3, 1.0, 4}), "");
  EXPECT_EQ(field_of({}, {0, 0, 0, 0.0, 0}), "keyframes");
  EXPECT_EQ(field_of({0}, {0, 0, 0, 0.0, 0}),
            "lifecycle/extinction_start");  // no extinction keyframe
  EXPECT_EQ(field_of(t, {-1, 2, 3, 1.0, 4}), "lifecycle/init_end");
  EXPECT_EQ(field_of(t, {5, 2, 3, 1.0, 4}), "lifecycle/init_end");
  EXPECT_EQ(field_of(t, {3, 2, 3, 1.0, 4}), "lifecycle/loop_start");
  EXPECT_EQ(field_of(t, {1, 3, 2, 1.0, 4}), "lifecycle/loop_end");
  EXPECT_EQ(field_of(t, {1, 2, 5, 1.0, 4}), "lifecycle/loop_end");
  EXPECT_EQ(field_of(t, {1, 2, 3, 1.0, 3}), "lifecycle/extinction_start");
  EXPECT_EQ(field_of(t, {1, 2, 3, 1.0, 5}), "lifecycle/extinction_start");
  EXPECT_EQ(field_of(t, {1, 2, 3, -1.0, 4}), "lifecycle/loop_wrap");
  EXPECT_EQ(field_of(t, {1, 2, 3, 0.0, 4}), "lifecycle/loop_wrap");  // a jump is no interpolation
  EXPECT_EQ(field_of(t, {1, 2, 3, std::nan(""), 4}), "lifecycle/loop_wrap");
  EXPECT_EQ(field_of(t, {1, 2, 3, INFINITY, 4}), "lifecycle/loop_wrap");
  EXPECT_EQ(field_of({0, 1, 2, 2, 4}, {1, 2, 3, 1.0, 4}), "keyframes/3/time");
  EXPECT_EQ(field_of({0, 1, 2, 1.5, 4}, {1, 2, 3, 1.0, 4}), "keyframes/3/time");
  EXPECT_EQ(field_of({-1, 1, 2, 3, 4}, {1, 2, 3, 1.0, 4}), "keyframes/0/time");
  EXPECT_EQ(field_of({0, 1, INFINITY, 3, 4}, {1, 2, 3, 1.0, 4}), "keyframes/2/time");
}

}  // namespace
}  // namespace obscura
