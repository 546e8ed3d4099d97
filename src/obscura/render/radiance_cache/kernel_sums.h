#pragma once
// The splat kernels' σs integrals on a lattice laid on its cloud's grid
// (RadianceCache's denominators and first moments, docs/physics.md): per
// node n and medium sample,
//
//   S0(n) = Σ_d ox(n, d) oy(n, d) oz(n, d) σs(n + d),
//   Sa(n) = the same with the axis-a factor's first moment,
//
// over the offsets d in [−r, r]³, σs at the nodes (zero outside the lattice
// and in blocks it does not hold). The weights are products of one factor
// per axis, so each sum is three one-dimensional passes (along x, then y,
// then z) over the lattice's box, the four sums sharing their first passes:
// nine passes of 2r + 1 multiply-adds per node instead of 4 (2r + 1)³. The
// same sums, added in another order.
#include <array>
#include <cstddef>
#include <vector>

#include "obscura/render/lattice/node_lattice.h"

namespace obscura {

// Per lattice node along one axis, 2r + 1 values for the offsets −r…r: the
// kernel's overlap with the node's neighbours and its first moment.
struct AxisOverlaps {
  std::vector<double> weight, moment;
};

// Whether the passes' dense arrays over `lattice`'s box (six doubles per
// node) stay within a quarter of the records' memory, which a sparse
// lattice's box need not.
bool kernel_sums_fit(const NodeLattice& lattice);

// Writes, for every slot of `lattice` and each of the `samples` medium
// samples of `sigma_s` (per slot, then sample; the nodes' σs), the four
// values S0, Sx, Sy, Sz into out[(slot · samples + k) · 4 + q].
void kernel_sums(const NodeLattice& lattice, int r, const std::array<AxisOverlaps, 3>& overlaps,
                 const std::vector<float>& sigma_s, int samples, int threads,
                 std::vector<float>& out);

}  // namespace obscura
