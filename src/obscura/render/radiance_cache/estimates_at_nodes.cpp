#include "obscura/render/radiance_cache/estimates_at_nodes.h"

#include <algorithm>
#include <cmath>

#include "obscura/core/check.h"
#include "obscura/core/parallel.h"

namespace obscura {
namespace {

// Solves Pᵀ w = d for w by Cramer's rule; false where P is nearly singular
// (a pair's centroids less than a quarter spacing apart, say).
bool solve_transposed(const std::array<std::array<double, 3>, 3>& p, const std::array<double, 3>& d,
                      std::array<double, 3>& w) {
  // m = Pᵀ.
  auto m = [&](int i, int j) { return p[j][i]; };
  auto det3 = [&](auto&& at) {
    return at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) -
           at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
           at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  };
  const double det = det3(m);
  if (!(std::abs(det) > 0.25 * 0.25 * 0.25)) return false;
  for (int k = 0; k < 3; ++k)
    w[k] = det3([&](int i, int j) { return j == k ? d[i] : m(i, j); }) / det;
  return true;
}

}  // namespace

std::vector<double> move_to_nodes(const NodeLattice& lattice, const KernelEstimates& estimates,
                                  int threads) {
  const std::size_t slots = lattice.slot_count(), n = estimates.channels;
  OBSCURA_CHECK(estimates.value.size() == slots * n && estimates.shift.size() == slots &&
                estimates.held.size() == slots && n > 0);
  const std::vector<std::uint8_t>& held = estimates.held;
  std::vector<double> moved(slots * n, 0.0);
  parallel_for(lattice.block_count(), threads, [&](std::size_t block) {
    for (std::size_t slot = block * NodeLattice::kBlockNodes;
         slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
      if (!held[slot]) continue;
      const double* v = estimates.value.data() + slot * n;
      double* out = moved.data() + slot * n;
      std::copy(v, v + n, out);
      const std::array<int, 3> node = lattice.slot_node(slot);
      const std::array<double, 3>& d = estimates.shift[slot];
      if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) continue;
      // Per axis a, the pair of estimates across the node (itself where a
      // neighbour has none): their centroids' difference is row a of P, their
      // values' difference row a of V, and the gradient G solves P G = V.
      // An axis with neither neighbour gets the row e_a and no change.
      std::array<std::array<double, 3>, 3> rows{};
      std::array<std::size_t, 3> from{}, to{};
      for (int a = 0; a < 3; ++a) {
        std::array<int, 3> lo = node, hi = node;
        --lo[a];
        ++hi[a];
        std::size_t below = lattice.slot_of(lo[0], lo[1], lo[2]),
                    above = lattice.slot_of(hi[0], hi[1], hi[2]);
        if (below != NodeLattice::kNoSlot && !held[below]) below = NodeLattice::kNoSlot;
        if (above != NodeLattice::kNoSlot && !held[above]) above = NodeLattice::kNoSlot;
        from[a] = below != NodeLattice::kNoSlot ? below : slot;
        to[a] = above != NodeLattice::kNoSlot ? above : slot;
        if (from[a] == to[a]) {
          rows[a][a] = 1.0;
          continue;
        }
        // The two centroids' offsets plus the nodes' own distance, 1 or 2.
        const double step = (to[a] != slot ? 1.0 : 0.0) + (from[a] != slot ? 1.0 : 0.0);
        for (int b = 0; b < 3; ++b) {
          rows[a][b] =
              estimates.shift[to[a]][b] - estimates.shift[from[a]][b] + (b == a ? step : 0.0);
        }
      }
      // The move −d·G = −d·P⁻¹V = −(P⁻ᵀd)·V: one solve for all channels.
      std::array<double, 3> weight;
      if (!solve_transposed(rows, d, weight)) continue;
      for (int a = 0; a < 3; ++a) {
        if (from[a] == to[a] || weight[a] == 0.0) continue;
        const double* vf = estimates.value.data() + from[a] * n;
        const double* vt = estimates.value.data() + to[a] * n;
        for (std::size_t c = 0; c < n; ++c) out[c] -= weight[a] * (vt[c] - vf[c]);
      }
      if (out[0] < 0.0) std::copy(v, v + n, out);
    }
  });
  return moved;
}

}  // namespace obscura
