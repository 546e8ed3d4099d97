// Kernel estimates moved from their kernels' centroids to their nodes
// (render/radiance_cache/estimates_at_nodes.h): a linear light field read at
// shifted centroids comes back exactly at the nodes, at the lattice's edges
// too (one-sided slopes); an estimate the move would make negative is kept.
#include "obscura/render/radiance_cache/estimates_at_nodes.h"

#include <gtest/gtest.h>

#include "obscura/core/rng.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

struct Field {
  std::array<double, 2> at0;
  std::array<std::array<double, 3>, 2> gradient;  // per channel, per node unit
  double operator()(int c, const std::array<double, 3>& x) const {
    return at0[c] + gradient[c][0] * x[0] + gradient[c][1] * x[1] + gradient[c][2] * x[2];
  }
};

TEST(EstimatesAtNodes, ALinearFieldReadAtTheCentroidsComesBackAtTheNodes) {
  const HomogeneousMedium medium(BBox3({0, 0, 0}, {1.0, 0.7, 0.5}), {0.5}, {0.1}, {1.0}, {0.0},
                                 0.0);
  const NodeLattice lattice(medium, 0.1, 0.0, 1u << 20);
  const std::size_t slots = lattice.slot_count();
  const Field field{{50.0, -3.0}, {{{0.7, -0.4, 1.1}, {0.2, 0.3, -0.5}}}};
  KernelEstimates e;
  e.channels = 2;
  e.value.assign(slots * 2, 0.0);
  e.shift.assign(slots, {0.0, 0.0, 0.0});
  e.held.assign(slots, 0);
  Rng rng(7, 0);
  int rim = 0;
  for (std::size_t slot = 0; slot < slots; ++slot) {
    if (!lattice.slot_inside(slot)) continue;
    const std::array<int, 3> n = lattice.slot_node(slot);
    std::array<double, 3> at{};
    for (int a = 0; a < 3; ++a) {
      // The rim's clipped kernels lie 2/3 of a spacing inside, the next
      // nodes' 2/21; elsewhere a random shift (a lopsided σs).
      const int last = lattice.dims()[a] - 1;
      double d = 0.3 * (2.0 * rng.uniform() - 1.0);
      if (n[a] == 0) d = 2.0 / 3.0;
      if (n[a] == last) d = -2.0 / 3.0;
      if (n[a] == 1) d = 2.0 / 21.0;
      if (n[a] == last - 1) d = -2.0 / 21.0;
      rim += n[a] == 0;
      e.shift[slot][a] = d;
      at[a] = n[a] + d;
    }
    e.held[slot] = 1;
    for (int c = 0; c < 2; ++c) e.value[slot * 2 + c] = field(c, at);
  }
  ASSERT_GT(rim, 20);
  for (const int threads : {1, 2}) {
    const std::vector<double> moved = move_to_nodes(lattice, e, threads);
    for (std::size_t slot = 0; slot < slots; ++slot) {
      if (!lattice.slot_inside(slot)) {
        EXPECT_EQ(moved[slot * 2], 0.0);
        continue;
      }
      const std::array<int, 3> n = lattice.slot_node(slot);
      const std::array<double, 3> at{1.0 * n[0], 1.0 * n[1], 1.0 * n[2]};
      for (int c = 0; c < 2; ++c)
        ASSERT_NEAR(moved[slot * 2 + c], field(c, at), 1e-12 * 50.0)
            << "slot " << slot << " node " << n[0] << ' ' << n[1] << ' ' << n[2];
    }
  }
}

TEST(EstimatesAtNodes, AMoveThatWouldMakeTheIsotropicTermNegativeIsNotMade) {
  const HomogeneousMedium medium(BBox3({0, 0, 0}, {0.5, 0.5, 0.5}), {0.5}, {0.1}, {1.0}, {0.0},
                                 0.0);
  const NodeLattice lattice(medium, 0.1, 0.0, 1u << 20);
  const std::size_t slots = lattice.slot_count();
  KernelEstimates e;
  e.channels = 1;
  e.value.assign(slots, 0.0);
  e.shift.assign(slots, {0.0, 0.0, 0.0});
  e.held.assign(slots, 0);
  const std::size_t a = lattice.slot_of(2, 2, 2), b = lattice.slot_of(3, 2, 2),
                    c = lattice.slot_of(1, 2, 2);
  e.held[a] = e.held[b] = e.held[c] = 1;
  e.value[a] = 1.0;
  e.value[b] = 10.0;  // steeply up along x
  e.value[c] = 0.0;
  // a sits 0.9 ahead: between its neighbours' centroids at −1 and 1.5 the
  // slope is 10/2.5, and 1 − 0.9 · 4 < 0.
  e.shift[a] = {0.9, 0.0, 0.0};
  e.shift[b] = {0.5, 0.0, 0.0};
  const std::vector<double> moved = move_to_nodes(lattice, e, 1);
  EXPECT_EQ(moved[a], 1.0);
  EXPECT_EQ(moved[c], 0.0);  // no shift, no move
  // b: one-sided (no neighbour above), its centroid at 0.5 and a's at −0.1.
  EXPECT_NEAR(moved[b], 10.0 - 0.5 * (10.0 - 1.0) / (0.5 - (0.9 - 1.0)), 1e-12);
}

}  // namespace
}  // namespace obscura
