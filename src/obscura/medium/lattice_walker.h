#pragma once
// 3-D digital differential analyser (Amanatides & Woo 1987, "A Fast Voxel
// Traversal Algorithm"): visits, in order, every cell of a regular lattice that
// the line p(t) = o + t d crosses for t in [t_begin, t_end], with the exact
// entry and exit parameters of each. Cells have side `cell_size` in the
// lattice's coordinates; indices are clamped to [lo, hi] (inclusive). Runs on
// a CUDA device too (core/host_device.h): the lattice march's.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "obscura/core/host_device.h"
#include "obscura/core/vec3.h"

namespace obscura {

class LatticeWalker {
 public:
  OBSCURA_HOST_DEVICE LatticeWalker(const Vec3& o, const Vec3& d, double t_begin, double t_end,
                                    double cell_size, const std::array<int, 3>& lo,
                                    const std::array<int, 3>& hi)
      : o_{o.x, o.y, o.z},
        d_{d.x, d.y, d.z},
        t_(t_begin),
        t_end_(t_end),
        cell_size_(cell_size),
        lo_(lo),
        hi_(hi) {
    const Vec3 p = o + d * t_begin;
    for (int a = 0; a < 3; ++a) {
      cell_[a] = std::clamp(static_cast<int>(std::floor(p[a] / cell_size)), lo[a], hi[a]);
      if (d[a] > 0) {
        step_[a] = 1;
      } else if (d[a] < 0) {
        step_[a] = -1;
      } else {
        step_[a] = 0;
      }
      t_next_[a] = next_crossing(a);
    }
  }

  // Writes the next cell and its [t0, t1]; false when the range is exhausted.
  OBSCURA_HOST_DEVICE bool next(std::array<int, 3>& cell, double& t0, double& t1) {
    int exit_axis;
    return next(cell, t0, t1, exit_axis);
  }
  // The same, and the axis of the cell's face the line leaves it through at
  // t1 (−1 where t1 is the range's end inside the cell).
  OBSCURA_HOST_DEVICE bool next(std::array<int, 3>& cell, double& t0, double& t1, int& exit_axis) {
    if (done_ || !(t_ < t_end_)) return false;
    int axis = 0;
    if (t_next_[1] < t_next_[axis]) axis = 1;
    if (t_next_[2] < t_next_[axis]) axis = 2;
    cell = cell_;
    t0 = t_;
    exit_axis = t_next_[axis] <= t_end_ ? axis : -1;
    t1 = std::min(t_next_[axis], t_end_);
    // Guard against a crossing computed marginally before t_ by rounding.
    if (t1 < t0) t1 = t0;
    t_ = t1;
    if (t_next_[axis] >= t_end_) {
      done_ = true;
    } else {
      cell_[axis] += step_[axis];
      if (cell_[axis] < lo_[axis] || cell_[axis] > hi_[axis]) done_ = true;
      t_next_[axis] = next_crossing(axis);
    }
    return true;
  }

 private:
  OBSCURA_HOST_DEVICE double next_crossing(int a) const {
    if (step_[a] == 0) return std::numeric_limits<double>::infinity();
    const double plane = (step_[a] > 0 ? cell_[a] + 1 : cell_[a]) * cell_size_;
    return std::max((plane - o_[a]) / d_[a], t_);
  }

  // As arrays, not Vec3: indexed by a runtime axis, Vec3's operator[] is a
  // chain of selects on the hot path of every step.
  std::array<double, 3> o_, d_;
  double t_, t_end_, cell_size_;
  std::array<int, 3> lo_, hi_;
  std::array<int, 3> cell_{}, step_{};
  std::array<double, 3> t_next_{};
  bool done_ = false;
};

}  // namespace obscura
