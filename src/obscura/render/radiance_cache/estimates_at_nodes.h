#pragma once
// The radiance cache's kernel estimates read at their nodes (docs/physics.md,
// "Estimates at the kernels' centroids"). A node's estimate
// Σ ΔΦ Y K / ∫ K σs dV is the σs-weighted mean of the light under its kernel:
// to first order the light at the kernel's σs-weighted centroid, not at the
// node. Where σs is lopsided under the kernel the two differ: at a
// scattering cloud's face the clipped kernel of a rim node has its centroid
// 2/3 of a spacing inside, the next node's 2/21, and the light, which falls
// towards the face, read +3 to +5 % high along the smoke cube's shadowed
// silhouette. Each estimate is moved to its node along every lattice axis
// with the gradient of its neighbours' estimates at their centroids.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "obscura/render/lattice/node_lattice.h"

namespace obscura {

struct KernelEstimates {
  std::size_t channels = 0;                  // values per slot
  std::vector<double> value;                 // per slot, `channels` values (the first: c_00)
  std::vector<std::array<double, 3>> shift;  // per slot, centroid − node, node units
  std::vector<std::uint8_t> held;            // per slot, whether it has an estimate
};

// Per slot the estimates moved to the node, v − d·∇v, the gradient ∇v from
// the pairs of neighbours across the node along each axis (the node itself
// standing in for a missing neighbour): the differences of their values over
// the differences of their centroids, a 3 × 3 solve, so a field linear in
// space comes back exactly. An axis with no neighbour counts as flat; a move
// whose solve is near-singular, or that would make the first channel (the
// isotropic term) negative, is not made. Slots without an estimate are zero.
// Deterministic: every slot reads only the unmoved estimates.
std::vector<double> move_to_nodes(const NodeLattice& lattice, const KernelEstimates& estimates,
                                  int threads);

}  // namespace obscura
