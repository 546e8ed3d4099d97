#pragma once
// The camera march over a lattice's records (lattice_view.h), written once for
// the CPU and a CUDA device (core/host_device.h, docs/gpu.md): the lattice's
// cells along a ray in order, each integrated with the cell quadrature of the
// medium's own march (render/emission_absorption/cell_quadrature.h) at its
// entry, middle and exit, the entry reused from the previous cell's exit.
// Per point the corners' records are interpolated once per spectral node
// (one record of Stride floats each, not every sample's channels), and a
// Source turns the interpolated record into σt and the emissivity:
//
//   struct Source {
//     // From record `values` (Stride floats, interpolated at the point) of
//     // node j: σt (1/m) and the emissivity ε (W m⁻³ sr⁻¹ µm⁻¹: σa B(T),
//     // plus σs J with in-scattering).
//     void point(int j, const float* values, double& sigma_t, double& emissivity) const;
//     // Optional: a record channel holding an optical depth (the sun's) that
//     // ε falls off with as e^{−value}.
//     static constexpr int kSteepChannel = …;
//     // Optional: the scattering the source keeps in the ray's own
//     // direction, φ (1/m; delta-M), given by a point with a fifth
//     // argument: the radiance is then integrated with σt − φ and seen
//     // through the march's `attenuation`, while `transmittance` stays the
//     // line's exact e^{−τ} (add_cell_forward, cell_quadrature.h).
//     static constexpr bool kKeepsForward = true;
//     void point(int j, const float* values, double& sigma_t, double& emissivity,
//                double& forward) const;
//     // With kSteepChannel: the part of ε that falls off as e^{−steep
//     // channel}, `steep`, given apart at the cell's points, and alone at
//     // other points from a record of which only the first kSteepReads
//     // floats were interpolated (φ = 0 for a source without kKeepsForward).
//     static constexpr int kSteepReads = …;
//     void split_point(int j, const float* values, double& sigma_t, double& emissivity,
//                      double& forward, double& steep) const;
//     void steep_point(int j, const float* values, double& sigma_t, double& steep,
//                      double& forward) const;
//   };
//
// The cell quadrature fits a parabola to the source function through three
// points, which cannot follow e^{−τ} where τ changes by several units across
// the cell (a grazing sun on an optically thick cell: van de Hulst's problem
// 1d, τ 32 and μ0 0.1, read +24 % with a cell one optical depth thick, the
// sun's depth changing by 10 across it). So where the steep channel changes
// by more than 1 between a cell's entry and exit, the steep part of ε is
// integrated over equal pieces of the cell (cell_pieces, cell_quadrature.h),
// each alike, and the rest of ε (smooth: the records' trilinear channels)
// over the whole cell: the quadrature is linear in ε, so the two add up. A
// piece's points read only what the steep part needs (the sun's light: 2 of
// the radiance cache's 4 groups of channels, no harmonics): 32 % of the
// cache's march on the demo frame was its pieces when they read everything
// (docs/performance.md).
//
// Blocks the lattice does not hold and cells none of whose corners holds
// medium are skipped; they are zero. The CPU marches every node of a band
// along one ray (MaxNodes = kMaxSpectralNodes); a device thread marches one
// node (MaxNodes = 1), with the same arithmetic per node, so its state stays
// in registers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "obscura/core/host_device.h"
#include "obscura/core/ray.h"
#include "obscura/medium/lattice_walker.h"
#include "obscura/render/emission_absorption/cell_quadrature.h"
#include "obscura/render/lattice/lattice_view.h"

namespace obscura {

namespace lattice_march_detail {

// Source::kSteepChannel, or −1 when the source has none.
template <class Source>
constexpr int steep_channel() {
  if constexpr (requires { Source::kSteepChannel; })
    return Source::kSteepChannel;
  else
    return -1;
}

// The first slots of the 8 blocks at offsets (0|1, 0|1, 0|1) from block
// `block` (x fastest), `zero` where the lattice does not hold one: a cell's
// corners lie in them.
OBSCURA_HOST_DEVICE inline void neighbour_blocks(const LatticeView& lattice,
                                                 const std::array<int, 3>& block, std::size_t zero,
                                                 std::array<std::size_t, 8>& first) {
  const std::int32_t* n = lattice.block_dims;
  for (int c = 0; c < 8; ++c) {
    const int bx = block[0] + (c & 1), by = block[1] + (c >> 1 & 1), bz = block[2] + (c >> 2 & 1);
    const std::size_t s =
        bx < n[0] && by < n[1] && bz < n[2] ? lattice.block_first_slot(bx, by, bz) : zero;
    first[c] = s == LatticeView::kNoSlot ? zero : s;
  }
}

// The 8 corner slots of the cell whose min corner is at `local` (0…7 per
// axis) in the block (held by the lattice) whose neighbours are `first`. A corner in a block the
// lattice does not hold reads the zero record, which every node of such a
// block is.
OBSCURA_HOST_DEVICE inline void corner_slots(const std::array<std::size_t, 8>& first,
                                             std::size_t zero, const std::array<int, 3>& local,
                                             std::array<std::size_t, 8>& slot) {
  constexpr int b = LatticeView::kBlock;
  if (local[0] < b - 1 && local[1] < b - 1 && local[2] < b - 1) {
    const std::size_t s =
        first[0] + static_cast<std::size_t>(local[0] + b * (local[1] + b * local[2]));
    slot = {s, s + 1, s + b, s + b + 1, s + b * b, s + b * b + 1, s + b * b + b, s + b * b + b + 1};
    return;
  }
  // A corner on a block's far face lies in the neighbouring block, at
  // offset 0 across that face: per axis the two corners' offsets in their
  // blocks and which block.
  int offset[3][2], side[3][2];
  constexpr int kScale[3] = {1, b, b * b};
  for (int a = 0; a < 3; ++a) {
    const int next = local[a] + 1;
    offset[a][0] = local[a] * kScale[a];
    offset[a][1] = (next & (b - 1)) * kScale[a];
    side[a][0] = 0;
    side[a][1] = (next / b) << a;
  }
  for (int c = 0; c < 8; ++c) {
    const int cx = c & 1, cy = c >> 1 & 1, cz = c >> 2 & 1;
    const std::size_t base = first[side[0][cx] | side[1][cy] | side[2][cz]];
    slot[c] = base == zero
                  ? zero
                  : base + static_cast<std::size_t>(offset[0][cx] + offset[1][cy] + offset[2][cz]);
  }
}

#if OBSCURA_DEVICE_CODE
// out[0…3] = value(&float4::x … &float4::w): a device's per-lane sums of
// float4 records (CUDA's float4 has no arithmetic of its own).
template <class Value>
__device__ inline void store_lanes(float* out, Value&& value) {
  out[0] = value(&float4::x);
  out[1] = value(&float4::y);
  out[2] = value(&float4::z);
  out[3] = value(&float4::w);
}
#endif

// The trilinear interpolation, at fractions f (0…1 per axis) across the
// cell whose corners' records (x fastest) are at `slot`, of the first Count
// floats of records Stride floats apart, four floats at a time (GCC/Clang
// vector extensions on the CPU, SSE on any x86-64; 16-byte loads on a
// device, where records are 16-byte aligned: Stride is a multiple of 4 and
// device buffers start 256-byte aligned), in one of two forms with the same
// code on the CPU and a device (so that their bits agree):
//  * interpolate_lerps, for records of one group of four (the medium's
//    channels): lerps along x, then y, then z, seven of them, whose chain
//    (three lerps) is what the march waits on;
//  * interpolate with the eight corners' weights, computed once per point
//    (corner_weights) and shared by every group and spectral node the point
//    reads, for longer records (the radiance cache's): per group 8 multiplies
//    and 7 adds summed pairwise, against the lerps' 7 subtractions, 7
//    multiplies and 7 adds (callgrind, docs/performance.md).
template <int Stride, int Count = Stride>
OBSCURA_HOST_DEVICE inline void interpolate_lerps(const float* records,
                                                  const std::array<std::size_t, 8>& slot,
                                                  const float f[3], float* out) {
  static_assert(Stride % 4 == 0 && Count % 4 == 0 && Count <= Stride);
#if OBSCURA_DEVICE_CODE
  auto lerp = [](const float4& a, const float4& b, float t) {
    return make_float4(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z),
                       a.w + t * (b.w - a.w));
  };
  for (int q = 0; q < Count / 4; ++q) {
    float4 r[8];
    for (int c = 0; c < 8; ++c)
      r[c] = __ldg(reinterpret_cast<const float4*>(records + slot[c] * Stride) + q);
    const float4 v = lerp(lerp(lerp(r[0], r[1], f[0]), lerp(r[2], r[3], f[0]), f[1]),
                          lerp(lerp(r[4], r[5], f[0]), lerp(r[6], r[7], f[0]), f[1]), f[2]);
    out[4 * q] = v.x;
    out[4 * q + 1] = v.y;
    out[4 * q + 2] = v.z;
    out[4 * q + 3] = v.w;
  }
#else
  using Float4 = float __attribute__((vector_size(16)));
  const Float4 fx = {f[0], f[0], f[0], f[0]}, fy = {f[1], f[1], f[1], f[1]},
               fz = {f[2], f[2], f[2], f[2]};
  auto lerp = [](const Float4& a, const Float4& b, const Float4& t) { return a + t * (b - a); };
  for (int q = 0; q < Count / 4; ++q) {
    Float4 r[8];
    for (int c = 0; c < 8; ++c) std::memcpy(&r[c], records + slot[c] * Stride + 4 * q, sizeof r[c]);
    const Float4 v = lerp(lerp(lerp(r[0], r[1], fx), lerp(r[2], r[3], fx), fy),
                          lerp(lerp(r[4], r[5], fx), lerp(r[6], r[7], fx), fy), fz);
    std::memcpy(out + 4 * q, &v, sizeof v);
  }
#endif
}

// The eight corners' weights at fractions f, corner c = x + 2y + 4z.
struct CornerWeights {
  float w[8];
};

OBSCURA_HOST_DEVICE inline CornerWeights corner_weights(const float f[3]) {
  const float gx = 1.0f - f[0], gy = 1.0f - f[1], gz = 1.0f - f[2];
  const float xy[4] = {gx * gy, f[0] * gy, gx * f[1], f[0] * f[1]};
  CornerWeights out;
  for (int c = 0; c < 4; ++c) {
    out.w[c] = xy[c] * gz;
    out.w[c + 4] = xy[c] * f[2];
  }
  return out;
}

template <int Stride, int Count = Stride>
OBSCURA_HOST_DEVICE inline void interpolate(const float* records,
                                            const std::array<std::size_t, 8>& slot,
                                            const CornerWeights& weights, float* out) {
  static_assert(Stride % 4 == 0 && Count % 4 == 0 && Count <= Stride);
  const float* w = weights.w;
#if OBSCURA_DEVICE_CODE
  for (int q = 0; q < Count / 4; ++q) {
    float4 r[8];
    for (int c = 0; c < 8; ++c)
      r[c] = __ldg(reinterpret_cast<const float4*>(records + slot[c] * Stride) + q);
    store_lanes(out + 4 * q, [&](float float4::*lane) {
      return ((w[0] * r[0].*lane + w[1] * r[1].*lane) + (w[2] * r[2].*lane + w[3] * r[3].*lane)) +
             ((w[4] * r[4].*lane + w[5] * r[5].*lane) + (w[6] * r[6].*lane + w[7] * r[7].*lane));
    });
  }
#else
  using Float4 = float __attribute__((vector_size(16)));
  Float4 wc[8];
  for (int c = 0; c < 8; ++c) wc[c] = Float4{} + w[c];
  for (int q = 0; q < Count / 4; ++q) {
    Float4 r[8];
    for (int c = 0; c < 8; ++c) std::memcpy(&r[c], records + slot[c] * Stride + 4 * q, sizeof r[c]);
    const Float4 v = ((wc[0] * r[0] + wc[1] * r[1]) + (wc[2] * r[2] + wc[3] * r[3])) +
                     ((wc[4] * r[4] + wc[5] * r[5]) + (wc[6] * r[6] + wc[7] * r[7]));
    std::memcpy(out + 4 * q, &v, sizeof v);
  }
#endif
}

// Interpolates a whole record of Stride floats at fractions f in the form
// for its length (above).
template <int Stride>
struct RecordInterpolation {
  static constexpr bool kByWeights = Stride > 4;
  CornerWeights weights;
  const float* f;
  OBSCURA_HOST_DEVICE explicit RecordInterpolation(const float fractions[3]) : f(fractions) {
    if constexpr (kByWeights) weights = corner_weights(fractions);
  }
  OBSCURA_HOST_DEVICE void operator()(const float* records, const std::array<std::size_t, 8>& slot,
                                      float* out) const {
    first<Stride>(records, slot, out);
  }
  // The first Count floats of the record only.
  template <int Count>
  OBSCURA_HOST_DEVICE void first(const float* records, const std::array<std::size_t, 8>& slot,
                                 float* out) const {
    if constexpr (kByWeights)
      interpolate<Stride, Count>(records, slot, weights, out);
    else
      interpolate_lerps<Stride, Count>(records, slot, f, out);
  }
};

// The interpolation on a face of the cell, across axis `axis` at its lower
// (side 0) or upper (side 1) plane: the bilinear interpolation of the face's
// four corners at the other two axes' fractions, in the same two forms as a
// point inside the cell (three lerps, or four weights), half the loads and
// arithmetic. A march's cell exits through a face (LatticeWalker::next's
// exit axis), and that point is the next cell's entry.
template <int Stride>
struct FaceInterpolation {
  static constexpr bool kByWeights = Stride > 4;
  int corner[4];  // the face's corners (c = x + 2y + 4z), the lower other axis fastest
  float fu, fv;   // the fractions along the other two axes, lower first
  float w[4];     // their bilinear weights (kByWeights)
  OBSCURA_HOST_DEVICE FaceInterpolation(int axis, int side, const float fractions[3])
      : fu(fractions[axis == 0 ? 1 : 0]), fv(fractions[axis == 2 ? 1 : 2]) {
    // Per axis and side the four corners, three bits each.
    constexpr unsigned kCorners[3][2] = {
        {0 | 2 << 3 | 4 << 6 | 6 << 9, 1 | 3 << 3 | 5 << 6 | 7 << 9},
        {0 | 1 << 3 | 4 << 6 | 5 << 9, 2 | 3 << 3 | 6 << 6 | 7 << 9},
        {0 | 1 << 3 | 2 << 6 | 3 << 9, 4 | 5 << 3 | 6 << 6 | 7 << 9}};
    const unsigned packed = kCorners[axis][side];
    for (int k = 0; k < 4; ++k) corner[k] = static_cast<int>(packed >> (3 * k) & 7u);
    if constexpr (kByWeights) {
      const float gu = 1.0f - fu, gv = 1.0f - fv;
      w[0] = gu * gv;
      w[1] = fu * gv;
      w[2] = gu * fv;
      w[3] = fu * fv;
    }
  }
  OBSCURA_HOST_DEVICE void operator()(const float* records, const std::array<std::size_t, 8>& slot,
                                      float* out) const {
#if OBSCURA_DEVICE_CODE
    for (int q = 0; q < Stride / 4; ++q) {
      float4 r[4];
      for (int k = 0; k < 4; ++k)
        r[k] = __ldg(reinterpret_cast<const float4*>(records + slot[corner[k]] * Stride) + q);
      store_lanes(out + 4 * q, [&](float float4::*lane) {
        if constexpr (kByWeights)
          return (w[0] * r[0].*lane + w[1] * r[1].*lane) + (w[2] * r[2].*lane + w[3] * r[3].*lane);
        const float a = r[0].*lane + fu * (r[1].*lane - r[0].*lane);
        const float b = r[2].*lane + fu * (r[3].*lane - r[2].*lane);
        return a + fv * (b - a);
      });
    }
#else
    using Float4 = float __attribute__((vector_size(16)));
    for (int q = 0; q < Stride / 4; ++q) {
      Float4 r[4];
      for (int k = 0; k < 4; ++k)
        std::memcpy(&r[k], records + slot[corner[k]] * Stride + 4 * q, sizeof r[k]);
      Float4 v;
      if constexpr (kByWeights) {
        v = (Float4{} + w[0]) * r[0] + (Float4{} + w[1]) * r[1] +
            ((Float4{} + w[2]) * r[2] + (Float4{} + w[3]) * r[3]);
      } else {
        const Float4 u = Float4{} + fu, t = Float4{} + fv;
        const Float4 a = r[0] + u * (r[1] - r[0]), b = r[2] + u * (r[3] - r[2]);
        v = a + t * (b - a);
      }
      std::memcpy(out + 4 * q, &v, sizeof v);
    }
#endif
  }
};

// The fractions across `cell` (0…1 per axis) of lattice point o + t d (o
// and d as arrays: Vec3's operator[] with a loop's index is a chain of
// selects).
OBSCURA_HOST_DEVICE inline void cell_fractions(const double o[3], const double d[3], double t,
                                               const std::array<int, 3>& cell, float f[3]) {
  for (int a = 0; a < 3; ++a) {
    // Clamped against rounding, in the forms that compile to maxsd and
    // minsd (std::clamp compiles to branches).
    double x = o[a] + t * d[a] - cell[a];
    x = x > 0.0 ? x : 0.0;
    f[a] = static_cast<float>(x < 1.0 ? x : 1.0);
  }
}

// Source::kSteepReads: the floats of a record a steep_point reads.
template <class Source>
constexpr int steep_reads() {
  if constexpr (requires { Source::kSteepReads; })
    return Source::kSteepReads;
  else
    return 0;
}

// Source::kKeepsForward, or false when the source has none.
template <class Source>
constexpr bool keeps_forward() {
  if constexpr (requires { Source::kKeepsForward; })
    return Source::kKeepsForward;
  else
    return false;
}

// Calls visit(cell, t0, t1, slot, exit_axis) for the cells of the lattice
// along the lattice ray o + t d, t in [t_begin, t_end], in order, that have
// some corner holding medium and a positive length: first the 8³ blocks the
// lattice holds, then their cells. exit_axis: the axis of the face the ray
// leaves the cell through at t1, −1 where t1 is not on one of the cell's own
// face planes (the range's end).
template <class Visit>
OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE inline void for_each_cell(const LatticeView& lattice,
                                                                    const Vec3& o, const Vec3& dir,
                                                                    double t_begin, double t_end,
                                                                    Visit&& visit) {
  constexpr int kBlock = LatticeView::kBlock;
  const std::size_t zero_slot = lattice.zero_slot;
  const std::int32_t* dims = lattice.dims;
  const std::int32_t* block_dims = lattice.block_dims;
  std::array<std::size_t, 8> first;
  std::array<std::size_t, 8> slot;
  LatticeWalker blocks(o, dir, t_begin, t_end, kBlock, {0, 0, 0},
                       {block_dims[0] - 1, block_dims[1] - 1, block_dims[2] - 1});
  std::array<int, 3> block, cell;
  double tb0, tb1, t0, t1;
  while (blocks.next(block, tb0, tb1)) {
    if (lattice.block_first_slot(block[0], block[1], block[2]) == LatticeView::kNoSlot)
      continue;  // no medium within a node of it
    neighbour_blocks(lattice, block, zero_slot, first);
    std::array<int, 3> lo, hi;
    bool has_cells = true;
    for (int a = 0; a < 3; ++a) {
      lo[a] = block[a] * kBlock;
      hi[a] = std::min(lo[a] + kBlock - 1, dims[a] - 2);
      has_cells = has_cells && hi[a] >= lo[a];
    }
    if (!has_cells) continue;
    LatticeWalker walker(o, dir, tb0, tb1, 1.0, lo, hi);
    int exit_axis;
    while (walker.next(cell, t0, t1, exit_axis)) {
      if (!(t1 > t0)) continue;
      corner_slots(first, zero_slot, {cell[0] - lo[0], cell[1] - lo[1], cell[2] - lo[2]}, slot);
      bool any = false;
      for (int c = 0; c < 8; ++c) any = any || lattice.occupied[slot[c]] != 0;
      if (any) visit(cell, t0, t1, slot, exit_axis);
    }
  }
}

}  // namespace lattice_march_detail

// Adds to radiance[j] the radiance emitted and scattered towards the ray's
// origin over [0, t_max] and multiplies transmittance[j] by the line's e^{−τ},
// for `nodes` (≤ MaxNodes) spectral nodes whose records start at records[j].
// `lray` is in lattice coordinates (LatticeView::to_lattice, to_lattice_direction),
// its parameter in metres. A source that keeps forward scattering
// (Source::kKeepsForward) also multiplies attenuation[j] by the e^{−∫(σt − φ)}
// the radiance was seen through. Returns the cells visited.
template <int Stride, int MaxNodes, class Source>
OBSCURA_FLATTEN OBSCURA_HOST_DEVICE std::uint64_t march_lattice_ray(
    const LatticeView& lattice, const float* const* records, int nodes, const Ray& lray,
    double t_max, const Source& source, double* radiance, double* transmittance,
    double* attenuation = nullptr) {
  namespace d = lattice_march_detail;
  double t_begin = 0.0, t_end = t_max;
  if (!lattice.domain.intersect(lray, t_begin, t_end) || !(t_end > t_begin)) return 0;
  const int n = MaxNodes == 1 ? 1 : nodes;  // a constant for a device thread's one node

  // σt and ε at the cell's entry, middle and exit, per node: pointers into
  // `values_at`, the entry and exit swapped when the exit is reused (a
  // device thread's one node copies instead, so that it stays in registers).
  constexpr bool kForward = d::keeps_forward<Source>();
  constexpr int kSteep = d::steep_channel<Source>();
  constexpr bool kSplits = kSteep >= 0;
  static_assert(!kSplits || d::steep_reads<Source>() % 4 == 0, "kSteepReads: groups of four");
  double values_at[6 + (kForward ? 3 : 0) + (kSplits ? 3 : 0)][MaxNodes];
  double* sigma_t[3] = {values_at[0], values_at[1], values_at[2]};
  double* emissivity[3] = {values_at[3], values_at[4], values_at[5]};
  // φ at the three points (kForward only).
  double* forward[3] = {values_at[kForward ? 6 : 0], values_at[kForward ? 7 : 1],
                        values_at[kForward ? 8 : 2]};
  // ε's steep part at the three points (kSplits only).
  constexpr int kSteepAt = kForward ? 9 : 6;
  double* steep_emissivity[3] = {values_at[kSplits ? kSteepAt : 0],
                                 values_at[kSplits ? kSteepAt + 1 : 1],
                                 values_at[kSplits ? kSteepAt + 2 : 2]};
  float frac[3];
  // Zero beyond the record: a CPU source may read its last channels in
  // whole groups of four (HgConvolution::readable).
  float values[Stride + 4] = {};
  std::uint64_t cells = 0;
  double previous_end = -1.0;
  const Vec3& o = lray.origin;
  const Vec3& dir = lray.direction;
  const double o3[3] = {o.x, o.y, o.z}, d3[3] = {dir.x, dir.y, dir.z};
  // The steep channel's value at the cell's entry and exit, per node.
  double steep_at[2][MaxNodes] = {};
  // σt and ε (and the steep channel's value and ε's steep part) at a point
  // into slot p of the arrays, the records read there by `interpolate`
  // (RecordInterpolation, or FaceInterpolation where the point lies on a
  // face of the cell).
  auto evaluate_with = [&](const auto& interpolate, const std::array<std::size_t, 8>& slot, int p,
                           double* steep) OBSCURA_ALWAYS_INLINE {
    for (int j = 0; j < n; ++j) {
      interpolate(records[j], slot, values);
      if constexpr (kSplits) {
        double phi;
        source.split_point(j, values, sigma_t[p][j], emissivity[p][j], phi, steep_emissivity[p][j]);
        if constexpr (kForward) forward[p][j] = phi;
      } else if constexpr (kForward) {
        source.point(j, values, sigma_t[p][j], emissivity[p][j], forward[p][j]);
      } else {
        source.point(j, values, sigma_t[p][j], emissivity[p][j]);
      }
      if constexpr (kSplits)
        if (steep) steep[j] = values[kSteep];
    }
  };
  // … at lattice point o + t d of `cell`.
  auto evaluate = [&](const std::array<int, 3>& cell, const std::array<std::size_t, 8>& slot,
                      double t, int p, double* steep) OBSCURA_ALWAYS_INLINE {
    d::cell_fractions(o3, d3, t, cell, frac);
    evaluate_with(d::RecordInterpolation<Stride>(frac), slot, p, steep);
  };
  // The cell's exit, through the face across `axis` (the upper plane where
  // the ray runs up that axis).
  auto evaluate_exit = [&](const std::array<int, 3>& cell, const std::array<std::size_t, 8>& slot,
                           double t, int axis, double* steep) OBSCURA_ALWAYS_INLINE {
    d::cell_fractions(o3, d3, t, cell, frac);
    evaluate_with(d::FaceInterpolation<Stride>(axis, d3[axis] > 0.0 ? 1 : 0, frac), slot, 2, steep);
  };
  auto keep_exit_as_entry = [&]() OBSCURA_ALWAYS_INLINE {
    if constexpr (MaxNodes == 1) {
      sigma_t[0][0] = sigma_t[2][0];
      emissivity[0][0] = emissivity[2][0];
      if constexpr (kForward) forward[0][0] = forward[2][0];
      if constexpr (kSplits) steep_emissivity[0][0] = steep_emissivity[2][0];
    } else {
      std::swap(sigma_t[0], sigma_t[2]);
      std::swap(emissivity[0], emissivity[2]);
      if constexpr (kForward) std::swap(forward[0], forward[2]);
      if constexpr (kSplits) std::swap(steep_emissivity[0], steep_emissivity[2]);
    }
  };
  // Node j0's … j0 + count − 1's cell of length h.
  auto add = [&](double h, int count, const double* const st[3], const double* const fw[3],
                 const double* const em[3], int j0) OBSCURA_ALWAYS_INLINE {
    if constexpr (kForward)
      add_cell_forward(h, count, st, fw, em, radiance + j0, transmittance + j0, attenuation + j0);
    else
      add_cell(h, count, st, em, radiance + j0, transmittance + j0);
  };
  d::for_each_cell(
      lattice, o, dir, t_begin, t_end,
      [&](const std::array<int, 3>& cell, double t0, double t1,
          const std::array<std::size_t, 8>& slot, int exit_axis) OBSCURA_ALWAYS_INLINE {
        ++cells;
        const bool reuse = t0 == previous_end;
        if (reuse) {
          keep_exit_as_entry();
          if constexpr (kSplits)
            for (int j = 0; j < n; ++j) steep_at[0][j] = steep_at[1][j];
        } else {
          evaluate(cell, slot, t0, 0, steep_at[0]);
        }
        // (A record of one group of four reads its eight corners in fewer
        // instructions than picking the face's four costs: callgrind,
        // docs/performance.md.)
        if (Stride > 4 && exit_axis >= 0)
          evaluate_exit(cell, slot, t1, exit_axis, steep_at[1]);
        else
          evaluate(cell, slot, t1, 2, steep_at[1]);
        previous_end = t1;
        evaluate(cell, slot, 0.5 * (t0 + t1), 1, nullptr);
        // How many pieces each node's cell takes: decided per node,
        // so that a device thread marching one node does the same.
        bool any_cut = false;
        int pieces[MaxNodes];
        for (int j = 0; j < n; ++j) {
          pieces[j] = 1;
          if constexpr (kSplits) pieces[j] = cell_pieces(steep_at[1][j] - steep_at[0][j]);
          any_cut = any_cut || pieces[j] > 1;
        }
        if (!any_cut) {
          add(t1 - t0, n, sigma_t, forward, emissivity, 0);
          return;
        }
        for (int j = 0; j < n; ++j) {
          const double* st[3] = {sigma_t[0] + j, sigma_t[1] + j, sigma_t[2] + j};
          const double* fw[3] = {forward[0] + j, forward[1] + j, forward[2] + j};
          const double* em[3] = {emissivity[0] + j, emissivity[1] + j, emissivity[2] + j};
          if (pieces[j] == 1) {
            add(t1 - t0, 1, st, fw, em, j);
            continue;
          }
          if constexpr (kSplits) {
            // The steep part over equal pieces, each from its entry (the
            // last one's exit), middle and exit, for this node alone, seen
            // through the cell from its entry (the last piece's exit is the
            // cell's).
            double piece_st[3], piece_em[3], piece_fw[3] = {};
            piece_st[2] = sigma_t[0][j];
            piece_em[2] = steep_emissivity[0][j];
            if constexpr (kForward) piece_fw[2] = forward[0][j];
            const double step = (t1 - t0) / pieces[j];
            double steep_light = 0.0, seen = 1.0;
            for (int k = 0; k < pieces[j]; ++k) {
              const double a = t0 + k * step, b = k + 1 == pieces[j] ? t1 : a + step;
              piece_st[0] = piece_st[2];
              piece_em[0] = piece_em[2];
              piece_fw[0] = piece_fw[2];
              for (int p = 1; p < 3; ++p) {
                if (k + 1 == pieces[j] && p == 2) {  // the cell's own exit, read already
                  piece_st[2] = sigma_t[2][j];
                  piece_em[2] = steep_emissivity[2][j];
                  if constexpr (kForward) piece_fw[2] = forward[2][j];
                  continue;
                }
                d::cell_fractions(o3, d3, p == 1 ? 0.5 * (a + b) : b, cell, frac);
                d::RecordInterpolation<Stride>(frac).template first<d::steep_reads<Source>()>(
                    records[j], slot, values);
                source.steep_point(j, values, piece_st[p], piece_em[p], piece_fw[p]);
              }
              const CellEmission c = integrate_seen(b - a, piece_st, piece_fw, piece_em);
              steep_light += seen * c.emitted;
              seen *= c.transmittance;
            }
            if constexpr (kForward)
              radiance[j] += attenuation[j] * steep_light;
            else
              radiance[j] += transmittance[j] * steep_light;
            // The rest over the whole cell.
            const double smooth[3] = {emissivity[0][j] - steep_emissivity[0][j],
                                      emissivity[1][j] - steep_emissivity[1][j],
                                      emissivity[2][j] - steep_emissivity[2][j]};
            const double* sm[3] = {smooth, smooth + 1, smooth + 2};
            add(t1 - t0, 1, st, fw, sm, j);
          }
        }
      });
  return cells;
}

// The same for a world ray (its direction unit length, t_max in metres).
template <int Stride, int MaxNodes, class Source>
OBSCURA_HOST_DEVICE std::uint64_t march_lattice_view(const LatticeView& lattice,
                                                     const float* const* records, int nodes,
                                                     const Ray& ray, double t_max,
                                                     const Source& source, double* radiance,
                                                     double* transmittance,
                                                     double* attenuation = nullptr) {
  const Ray lray{lattice.to_lattice(ray.origin), lattice.to_lattice_direction(ray.direction)};
  return march_lattice_ray<Stride, MaxNodes>(lattice, records, nodes, lray, t_max, source, radiance,
                                             transmittance, attenuation);
}

// The optical depth ∫ σt along the lattice ray over [0, t_max] (σt = σa + σs
// of the records of Stride floats at `records`): Simpson's rule on each cell's
// entry, middle and exit, exact for the trilinear σt, a cubic along the line,
// over the same cells as the march. Reads only the medium channels, so the
// light channels of the same records may be written meanwhile (the sun's
// optical depths, gpu/sun_depth_job.h).
template <int Stride>
OBSCURA_HOST_DEVICE double lattice_optical_depth(const LatticeView& lattice, const float* records,
                                                 const Ray& lray, double t_max) {
  namespace d = lattice_march_detail;
  double t_begin = 0.0, t_end = t_max;
  if (!lattice.domain.intersect(lray, t_begin, t_end) || !(t_end > t_begin)) return 0.0;
  double tau = 0.0;
  float frac[3];
  float values[record::kMediumStride];
  const Vec3& o = lray.origin;
  const Vec3& dir = lray.direction;
  const double o3[3] = {o.x, o.y, o.z}, d3[3] = {dir.x, dir.y, dir.z};
  double sigma_t[3] = {0.0, 0.0, 0.0};  // at the cell's entry, middle and exit
  double previous_end = -1.0;
  d::for_each_cell(
      lattice, o, dir, t_begin, t_end,
      [&](const std::array<int, 3>& cell, double t0, double t1,
          const std::array<std::size_t, 8>& slot, int /*exit_axis*/) OBSCURA_ALWAYS_INLINE {
        const bool reuse = t0 == previous_end;
        if (reuse) sigma_t[0] = sigma_t[2];
        const double ts[3] = {t0, 0.5 * (t0 + t1), t1};
        for (int p = reuse ? 1 : 0; p < 3; ++p) {
          d::cell_fractions(o3, d3, ts[p], cell, frac);
          d::interpolate_lerps<Stride, record::kMediumStride>(records, slot, frac, values);
          sigma_t[p] = static_cast<double>(values[record::kSigmaA]) + values[record::kSigmaS];
        }
        tau += (t1 - t0) / 6.0 * (sigma_t[0] + 4.0 * sigma_t[1] + sigma_t[2]);
        previous_end = t1;
      });
  return tau;
}

}  // namespace obscura
