#pragma once
// The camera march over a LatticeVolume (lattice_volume.h): the lattice's
// cells along a ray in order, each integrated with the cell quadrature of the
// medium's own march (render/emission_absorption/cell_quadrature.h) at its
// entry, middle and exit, the entry reused from the previous cell's exit.
// Per point the corners' records are interpolated once per spectral node
// (one record of stride floats each, not every sample's channels), and a
// Source turns the interpolated record into σt and the emissivity:
//
//   struct Source {
//     // From record `values` (the volume's stride floats, interpolated at
//     // the point) of node j: σt (1/m) and the emissivity ε
//     // (W m⁻³ sr⁻¹ µm⁻¹: σa B(T), plus σs J with in-scattering).
//     void point(int j, const float* values, double& sigma_t, double& emissivity) const;
//   };
//
// Blocks the lattice does not hold and cells none of whose corners holds
// medium are skipped; they are zero. The volume must hold the medium
// (LatticeVolume::has_medium). The result equals the medium's own
// march (Medium::march_cells with the same cells) up to float rounding of
// the records: the cells, points and quadrature are the same.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <utility>

#include "obscura/core/ray.h"
#include "obscura/medium/lattice_walker.h"
#include "obscura/render/emission_absorption/cell_quadrature.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/spectral_nodes.h"

namespace obscura {

namespace lattice_march_detail {

// The first slots of the 8 blocks at offsets (0|1, 0|1, 0|1) from block
// `block` (x fastest), `zero` where the lattice does not hold one: a cell's
// corners lie in them.
inline void neighbour_blocks(const NodeLattice& lattice, const std::array<int, 3>& block,
                             std::size_t zero, std::array<std::size_t, 8>& first) {
  const std::array<int, 3>& n = lattice.block_dims();
  for (int c = 0; c < 8; ++c) {
    const int bx = block[0] + (c & 1), by = block[1] + (c >> 1 & 1), bz = block[2] + (c >> 2 & 1);
    const std::size_t s =
        bx < n[0] && by < n[1] && bz < n[2] ? lattice.block_first_slot(bx, by, bz) : zero;
    first[c] = s == NodeLattice::kNoSlot ? zero : s;
  }
}

// The 8 corner slots of the cell whose min corner is at `local` (0…7 per
// axis) in the block (held by the lattice) whose neighbours are `first`. A corner in a block the
// lattice does not hold reads the zero record, which every node of such a
// block is.
inline void corner_slots(const std::array<std::size_t, 8>& first, std::size_t zero,
                         const std::array<int, 3>& local, std::array<std::size_t, 8>& slot) {
  constexpr int b = NodeLattice::kBlock;
  if (local[0] < b - 1 && local[1] < b - 1 && local[2] < b - 1) {
    const std::size_t s =
        first[0] + static_cast<std::size_t>(local[0] + b * (local[1] + b * local[2]));
    slot = {s, s + 1, s + b, s + b + 1, s + b * b, s + b * b + 1, s + b * b + b, s + b * b + b + 1};
    return;
  }
  for (int c = 0; c < 8; ++c) {
    const int x = local[0] + (c & 1), y = local[1] + (c >> 1 & 1), z = local[2] + (c >> 2 & 1);
    const std::size_t base = first[(x >> 3) | (y >> 3) << 1 | (z >> 3) << 2];
    slot[c] = base == zero ? zero
                           : base + static_cast<std::size_t>((x & 7) + b * ((y & 7) + b * (z & 7)));
  }
}

// Σ_c w_c record_c over Stride floats, four at a time (GCC/Clang vector
// extensions: SSE on any x86-64, wider where the compiler is allowed).
template <int Stride>
inline void interpolate(const float* records, const std::array<std::size_t, 8>& slot,
                        const std::array<float, 8>& w, float* out) {
  static_assert(Stride % 4 == 0);
  using Float4 = float __attribute__((vector_size(16)));
  Float4 acc[Stride / 4] = {};
  for (int c = 0; c < 8; ++c) {
    const float* r = records + slot[c] * Stride;
    const Float4 wc = {w[c], w[c], w[c], w[c]};
    for (int q = 0; q < Stride / 4; ++q) {
      Float4 v;
      std::memcpy(&v, r + 4 * q, sizeof v);
      acc[q] += wc * v;
    }
  }
  std::memcpy(out, acc, sizeof acc);
}

}  // namespace lattice_march_detail

// Adds to radiance[j] the radiance emitted and scattered towards the ray's
// origin over [0, t_max] and multiplies transmittance[j] by the line's e^{−τ},
// for the `nodes` spectral nodes whose records are volume.records(record[j]).
// `volume.stride()` must be Stride. Returns the cells visited.
template <int Stride, class Source>
std::uint64_t march_lattice(const LatticeVolume& volume, const int* record, int nodes,
                            const Ray& ray, double t_max, const Source& source, double* radiance,
                            double* transmittance) {
  namespace d = lattice_march_detail;
  const NodeLattice& lattice = volume.lattice();
  const Ray lray{lattice.to_lattice(ray.origin), lattice.to_lattice_direction(ray.direction)};
  double t_begin = 0.0, t_end = t_max;
  if (!volume.domain().intersect(lray, t_begin, t_end) || !(t_end > t_begin)) return 0;

  std::array<const float*, kMaxSpectralNodes> records;
  for (int j = 0; j < nodes; ++j) records[j] = volume.records(record[j]);
  const std::uint8_t* occupied = volume.occupied();
  const std::size_t zero_slot = volume.zero_slot();
  const std::array<int, 3>& dims = lattice.dims();
  const std::array<int, 3>& block_dims = lattice.block_dims();
  constexpr int kBlock = NodeLattice::kBlock;

  // σt and ε at the cell's entry, middle and exit, per node (pointers into
  // `values_at`, the entry and exit swapped when the exit is reused).
  std::array<std::array<double, kMaxSpectralNodes>, 6> values_at;
  double* sigma_t[3] = {values_at[0].data(), values_at[1].data(), values_at[2].data()};
  double* emissivity[3] = {values_at[3].data(), values_at[4].data(), values_at[5].data()};
  std::array<std::size_t, 8> first;
  std::array<std::size_t, 8> slot;
  std::array<float, 8> w;
  float values[Stride];
  std::uint64_t cells = 0;
  double previous_end = -1.0;
  const Vec3& o = lray.origin;
  const Vec3& dir = lray.direction;

  LatticeWalker blocks(o, dir, t_begin, t_end, kBlock, {0, 0, 0},
                       {block_dims[0] - 1, block_dims[1] - 1, block_dims[2] - 1});
  std::array<int, 3> block, cell;
  double tb0, tb1, t0, t1;
  while (blocks.next(block, tb0, tb1)) {
    if (lattice.block_first_slot(block[0], block[1], block[2]) == NodeLattice::kNoSlot)
      continue;  // no medium within a node of it
    d::neighbour_blocks(lattice, block, zero_slot, first);
    std::array<int, 3> lo, hi;
    bool has_cells = true;
    for (int a = 0; a < 3; ++a) {
      lo[a] = block[a] * kBlock;
      hi[a] = std::min(lo[a] + kBlock - 1, dims[a] - 2);
      has_cells = has_cells && hi[a] >= lo[a];
    }
    if (!has_cells) continue;
    LatticeWalker walker(o, dir, tb0, tb1, 1.0, lo, hi);
    while (walker.next(cell, t0, t1)) {
      if (!(t1 > t0)) continue;
      d::corner_slots(first, zero_slot, {cell[0] - lo[0], cell[1] - lo[1], cell[2] - lo[2]}, slot);
      bool any = false;
      for (int c = 0; c < 8; ++c) any = any || occupied[slot[c]] != 0;
      if (!any) continue;
      ++cells;
      const bool reuse = t0 == previous_end;
      if (reuse) {
        std::swap(sigma_t[0], sigma_t[2]);
        std::swap(emissivity[0], emissivity[2]);
      }
      const double ts[3] = {t0, 0.5 * (t0 + t1), t1};
      for (int p = reuse ? 1 : 0; p < 3; ++p) {
        float f[3];
        for (int a = 0; a < 3; ++a)
          f[a] = static_cast<float>(std::clamp(o[a] + ts[p] * dir[a] - cell[a], 0.0, 1.0));
        const float x0 = 1 - f[0], y0 = 1 - f[1], z0 = 1 - f[2];
        w = {x0 * y0 * z0,   f[0] * y0 * z0,   x0 * f[1] * z0,   f[0] * f[1] * z0,
             x0 * y0 * f[2], f[0] * y0 * f[2], x0 * f[1] * f[2], f[0] * f[1] * f[2]};
        for (int j = 0; j < nodes; ++j) {
          d::interpolate<Stride>(records[j], slot, w, values);
          source.point(j, values, sigma_t[p][j], emissivity[p][j]);
        }
      }
      add_cell(t1 - t0, nodes, sigma_t, emissivity, radiance, transmittance);
      previous_end = t1;
    }
  }
  return cells;
}

}  // namespace obscura
