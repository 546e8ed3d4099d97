#pragma once
// Optical depths along one direction from every node of a lattice (the sun's
// depth at each node of the radiance cache, RadianceCache::compute_sun), with
// the walk shared by all of them.
//
// The rays from two nodes along the same direction are the same line shifted
// by a whole lattice vector, so they cross the same cells shifted by it, at
// the same parameters and the same fractions across each cell. One walk from
// node (0, 0, 0), the template, then serves every node: a node's depth is the
// sum over the template's cells, shifted by the node, of Simpson's rule on
// the trilinear σt at the cell's entry, middle and exit, as
// lattice_optical_depth does (lattice_view_march.h). Simpson's rule is
// linear in the eight corners' σt,
//
//   (t1 − t0)/6 (σt(x0) + 4 σt(xm) + σt(x1)) = Σ_c W_c σt_c,
//   W_c = (t1 − t0)/6 (w_c(x0) + 4 w_c(xm) + w_c(x1))
//
// (w_c the corner's trilinear weight), so the template stores each cell's
// W_c and a node's cell costs eight loads and eight multiply-adds per
// spectral node, from σt laid out densely per node. The walk, the cell
// fractions and the weights are paid once (docs/performance.md, "The sun's
// depths"). Equal to the march up to rounding; the last cell, where the ray
// leaves the medium's box, is cut there and weighted on its own.
//
// For points inside the medium's box, `domain`: every node of a lattice on a
// grid but the rim, and the rim's two points (rim_face, lattice_view.h): the
// box's point nearest a rim node, a node moved by ½ along the axes it lies
// beyond the box on (a template of its own per such set of axes), and its
// inner neighbour, a node. CPU only.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/ray.h"
#include "obscura/core/vec3.h"
#include "obscura/medium/lattice_walker.h"
#include "obscura/render/lattice/lattice_view.h"

namespace obscura {

class ParallelDepths {
 public:
  // Whether σt laid out over `lattice`'s whole box (a double per node and
  // spectral node) stays within the records' memory: the box holds at most
  // four times the lattice's held nodes, which a sparse lattice's need not.
  static bool fits(const LatticeView& lattice) {
    return static_cast<double>(lattice.dims[0]) * lattice.dims[1] * lattice.dims[2] <=
           4.0 * static_cast<double>(lattice.zero_slot);
  }

  // The templates for `lattice` along `direction` (lattice units per metre,
  // LatticeView::to_lattice_direction, so that depths come out per metre),
  // and σt = σa + σs of the records of `nodes` spectral nodes (`stride`
  // floats each, at records[j]) per lattice node.
  ParallelDepths(const LatticeView& lattice, const float* const* records, int nodes, int stride,
                 const Vec3& direction)
      : domain_(lattice.domain),
        dims_{lattice.dims[0], lattice.dims[1], lattice.dims[2]},
        direction_(direction),
        nodes_(nodes) {
    const std::array<int, 3>& n = dims_;
    const std::size_t count = static_cast<std::size_t>(n[0]) * n[1] * n[2];
    stride_ = {1, n[0], static_cast<std::ptrdiff_t>(n[0]) * n[1]};
    // σt per node, densely (x fastest), zero in the blocks the lattice does
    // not hold (there is no medium within a node of them).
    sigma_t_.assign(static_cast<std::size_t>(nodes) * count, 0.0);
    std::size_t i = 0;
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x, ++i) {
          const std::size_t slot = lattice.node_slot(x, y, z);
          if (slot == LatticeView::kNoSlot) continue;
          for (int j = 0; j < nodes; ++j) {
            const float* r = records[j] + slot * static_cast<std::size_t>(stride);
            sigma_t_[static_cast<std::size_t>(j) * count + i] =
                static_cast<double>(r[record::kSigmaA]) + r[record::kSigmaS];
          }
        }
    count_ = count;
    for (int half = 0; half < 8; ++half) walk_template(half);
  }

  // Adds to tau[j], j < the spectral nodes, the optical depth from lattice
  // point `node` + ½ `half` (½ along the axes of bits 1, 2, 4 of `half`: a
  // node, or the point of the medium's box nearest a rim node, rim_face)
  // along the direction. The point must lie in the medium's box.
  void add(const std::array<int, 3>& node, int half, double* tau) const {
    const double at[3] = {node[0] + 0.5 * (half & 1), node[1] + 0.5 * (half >> 1 & 1),
                          node[2] + 0.5 * (half >> 2 & 1)};
    double t_begin = 0.0, t_end = std::numeric_limits<double>::infinity();
    if (!domain_.intersect(Ray{Vec3(at[0], at[1], at[2]), direction_}, t_begin, t_end) ||
        !(t_end > 0.0))
      return;
    const std::ptrdiff_t base = node[0] * stride_[0] + node[1] * stride_[1] + node[2] * stride_[2];
    for (const Cell& c : cells_[static_cast<std::size_t>(half)]) {
      if (!(c.t0 < t_end)) break;
      // The last cell, cut where the ray leaves the box, is weighted on
      // its own.
      const bool cut = c.t1 > t_end;
      double cut_weights[8];
      if (cut) {
        const std::array<int, 3> cell = {node[0] + c.offset[0], node[1] + c.offset[1],
                                         node[2] + c.offset[2]};
        simpson_weights(at, cell, c.t0, t_end, cut_weights);
      }
      const double* w = cut ? cut_weights : c.weights;
      // Per spectral node, the corners pairwise along x (adjacent), summed
      // as a tree.
      const std::ptrdiff_t sy = stride_[1], sz = stride_[2];
      const double* s = sigma_t_.data() + (base + c.corner_offset);
      for (int j = 0; j < nodes_; ++j, s += count_)
        tau[j] += ((w[0] * s[0] + w[1] * s[1]) + (w[2] * s[sy] + w[3] * s[sy + 1])) +
                  ((w[4] * s[sz] + w[5] * s[sz + 1]) + (w[6] * s[sz + sy] + w[7] * s[sz + sy + 1]));
      if (cut) break;
    }
  }

  // The cells of the template from node (0, 0, 0) (for tests).
  std::size_t cell_count() const { return cells_[0].size(); }

 private:
  struct Cell {
    std::array<int, 3> offset;     // of the cell from the template's node
    std::ptrdiff_t corner_offset;  // of its min corner, densely
    double t0, t1;
    double weights[8];  // W_c (above), corner c = x + 2y + 4z
  };

  // W_c of `cell` over [t0, t1] of the line from `o` (lattice units) along
  // the direction: the trilinear weights at the entry, middle and exit, the
  // fractions clamped against rounding as the march's.
  void simpson_weights(const double o[3], const std::array<int, 3>& cell, double t0, double t1,
                       double* weights) const {
    const double d[3] = {direction_.x, direction_.y, direction_.z};
    const double ts[3] = {t0, 0.5 * (t0 + t1), t1};
    const double simpson[3] = {1.0, 4.0, 1.0};
    std::fill(weights, weights + 8, 0.0);
    for (int p = 0; p < 3; ++p) {
      double f[3];
      for (int a = 0; a < 3; ++a) f[a] = std::clamp(o[a] + ts[p] * d[a] - cell[a], 0.0, 1.0);
      for (int c = 0; c < 8; ++c) {
        double w = (t1 - t0) / 6.0 * simpson[p];
        for (int a = 0; a < 3; ++a) w *= (c >> a & 1) ? f[a] : 1.0 - f[a];
        weights[c] += w;
      }
    }
  }

  // The walk from ½ `half` (add), long enough to leave the lattice from any
  // node: a ray leaves it when it has crossed it along any one axis.
  void walk_template(int half) {
    const double d[3] = {direction_.x, direction_.y, direction_.z};
    const double o[3] = {0.5 * (half & 1), 0.5 * (half >> 1 & 1), 0.5 * (half >> 2 & 1)};
    double t_max = std::numeric_limits<double>::infinity();
    int reach = 0;
    for (int a = 0; a < 3; ++a) {
      if (d[a] != 0.0) t_max = std::min(t_max, (dims_[a] + 1.0) / std::abs(d[a]));
      reach = std::max(reach, dims_[a] + 1);
    }
    if (!(t_max < std::numeric_limits<double>::infinity())) return;  // no direction: no cells
    LatticeWalker walker(Vec3(o[0], o[1], o[2]), direction_, 0.0, t_max, 1.0,
                         {-reach, -reach, -reach}, {reach, reach, reach});
    std::vector<Cell>& cells = cells_[static_cast<std::size_t>(half)];
    std::array<int, 3> cell;
    double t0, t1;
    while (walker.next(cell, t0, t1)) {
      if (!(t1 > t0)) continue;
      Cell c;
      c.offset = cell;
      c.corner_offset = cell[0] * stride_[0] + cell[1] * stride_[1] + cell[2] * stride_[2];
      c.t0 = t0;
      c.t1 = t1;
      simpson_weights(o, cell, t0, t1, c.weights);
      cells.push_back(c);
    }
  }

  BBox3 domain_;             // the medium's box (LatticeView::domain)
  std::array<int, 3> dims_;  // the lattice's nodes per axis
  Vec3 direction_;
  int nodes_;
  std::size_t count_ = 0;                   // lattice nodes
  std::vector<double> sigma_t_;             // per spectral node, per lattice node (x fastest)
  std::array<std::vector<Cell>, 8> cells_;  // per `half`
  std::array<std::ptrdiff_t, 3> stride_;    // of a node's neighbours along x, y, z
};

}  // namespace obscura
