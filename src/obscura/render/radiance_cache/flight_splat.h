#pragma once
// The radiance cache's track-length splat (docs/physics.md, "The radiance
// cache"): every photon flight adds to each lattice node n of the cells it
// crosses
//   ΔΦ Y_lm(ω) ∫_flight K(x(t) − x_n) σs(x(t)) dt,
// where the collision splat adds ΔΦ Y_lm(ω) K(x_i − x_n) at the flight's
// scattering collision. The expectations are equal (scattering collisions
// happen at the rate σs along a track), so the same normalisation by
// ∫ K σs dV applies, but every flight reaches every node along it rather
// than one collision reaching the nodes around it: much less variance where
// a cell is optically thin (the classic track-length against collision
// estimator; Spanier & Gelbard 1969, "Monte Carlo principles and neutron
// transport problems", §3).
//
// For a lattice laid on the cloud's grid (σs trilinear in each cell, read
// from the records at the node's wavelength) and the tent kernel of one
// spacing (K the node's trilinear hat / h³), each cell piece of a flight is
// integrated by Gauss–Legendre in t: two points where σs is constant over the
// cell (the hat alone is a cubic: exact), three otherwise (degree 6: a
// relative error of order (Δσs/σs)² 10⁻⁴ over a cell).
//
// Deterministic and independent of the thread and process counts: the
// lattice is cut into fixed slabs of node layers across its longest axis, each
// summed by one task over the flights that reach it, in their stored order
// (in floats, 10⁻⁷ of each sum per addition, added to the double sums at the
// end: a node's harmonics then fill one cache line).
// Processes share the slabs (slab s on rank s mod N) and then exchange their
// slabs' sums, so each holds the bits one process would have made alone.
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/core/vec3.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/photon_map/photon.h"
#include "obscura/render/radiance_cache/light_region.h"

namespace obscura {

// The most sensors' viewing directions one splat serves with the phase
// function's forward peak (what the padding of a light record holds).
inline constexpr int kMaxPeakViews = 2;

// Adds every flight's contributions for spectral node `node` (records
// volume.records(node), which must hold the medium) to `sum`: per slot
// sh_coefficient_count(sh_degree) values, then one per direction ω of
// `peak_views` (unit, the direction light leaves towards a sensor; at most
// kMaxPeakViews): ΔΦ ∫_flight K σs q(ω_flight·ω; g) dt with q what the
// harmonics leave out of the phase function (hg_beyond_degree,
// cache_source.h) and g = (σs g)/σs along the flight. With `cells`, only
// the flights' parts in those cells are walked (light_region.h): the nodes
// more than one spacing inside the box get the same sums, those nearer its
// faces part of theirs. Every process of `processes` must call it with the
// same flights and box (a collective).
void splat_flights(const LatticeVolume& volume, int node, const std::vector<PhotonFlight>& flights,
                   int sh_degree, int threads, std::vector<double>& sum,
                   const ProcessGroup& processes = single_process(),
                   const std::vector<Vec3>& peak_views = {}, const CellBox* cells = nullptr);

// Turns the sums of splat_flights (the tent kernel of one spacing) into
// those of the tent kernel of r spacings, K_r(u) = Π_a max(0, 1 − |u_a|/(r h))
// / (r h)³. The wide tent is piecewise linear with its knots on the nodes,
// so on the lattice's hats it is exactly
//   K_r(u) = Σ_k w(k) K_1(u − k h),  w(k) = Π_a (1 − |k_a|/r) / r  (|k_a| < r),
// and the sums, linear in the kernel, are the same filter of the one-spacing
// sums: three passes, one per axis, in a fixed order (the result does not
// depend on the thread count; every process holds the same sums). Nodes the
// lattice does not hold add nothing (no medium there: their sums are zero).
// `sum` holds per_slot values per slot; r = 1 leaves it as it is.
void widen_splat(const NodeLattice& lattice, int r, std::size_t per_slot, int threads,
                 std::vector<double>& sum);

}  // namespace obscura
