#pragma once
// A LatticeVolume (lattice_volume.h) as plain pointers and numbers: what the
// lattice march reads (lattice_view_march.h), laid out identically by the host
// compiler and by nvcc so that it crosses to a CUDA device by value
// (docs/gpu.md). The host's view points into a LatticeVolume and its
// NodeLattice; a device's, into copies of the same arrays in device memory.
//
// Records: per spectral node, one record of `stride` floats per slot, its
// channels
//   [σa, σs, T, σs g, τ_sun, V_sun, c_00, c_1−1, c_10, …]
// (1/m, 1/m, K, 1/m, optical depth, 0…1, then the radiance cache's spherical-
// harmonic coefficients), and the zero record at slot zero_slot for every
// node of a block the lattice does not hold.
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "obscura/core/bbox.h"
#include "obscura/core/host_device.h"
#include "obscura/core/mat3.h"
#include "obscura/core/vec3.h"

namespace obscura {

// Channels of a record.
namespace record {
inline constexpr int kSigmaA = 0, kSigmaS = 1, kTemperature = 2, kSigmaSG = 3, kTauSun = 4,
                     kSunVisibility = 5, kSh = 6;
// Floats per record: the medium alone, and with the light at `sh_count`
// coefficients (rounded up to whole groups of four, for SIMD loads).
inline constexpr int kMediumStride = 4;
constexpr int light_stride(int sh_count) { return (kSh + sh_count + 3) / 4 * 4; }
}  // namespace record

struct LatticeView {
  static constexpr int kBlock = 8;  // nodes per block side (NodeLattice::kBlock)
  static constexpr int kBlockNodes = kBlock * kBlock * kBlock;
  static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);

  Vec3 origin_m;                    // world position of node (0, 0, 0)
  Mat3 to_lattice_axes;             // Rᵀ: world axes to the lattice's
  double spacing_m = 1.0;           // h
  std::int32_t dims[3] = {};        // nodes per axis
  std::int32_t block_dims[3] = {};  // blocks per axis
  // Per block of the lattice (x fastest): the index of its slot block, −1
  // where the lattice does not hold it.
  const std::int32_t* block_index = nullptr;
  // Per held block: its block coordinates.
  const std::array<int, 3>* blocks = nullptr;
  // Per slot and the zero slot: whether σa or σs is non-zero there.
  const std::uint8_t* occupied = nullptr;
  std::uint64_t zero_slot = 0;  // = the slot count
  BBox3 domain;                 // where the medium is, lattice coordinates

  // Lattice coordinates (node units) of a world point; a world direction in
  // node units per metre (so that a ray's parameter stays in metres).
  OBSCURA_HOST_DEVICE Vec3 to_lattice(const Vec3& p) const {
    return to_lattice_axes * (p - origin_m) / spacing_m;
  }
  OBSCURA_HOST_DEVICE Vec3 to_lattice_direction(const Vec3& d) const {
    return to_lattice_axes * d / spacing_m;
  }
  // The first slot of block (bx, by, bz), kNoSlot where it is not held.
  OBSCURA_HOST_DEVICE std::size_t block_first_slot(int bx, int by, int bz) const {
    const std::int32_t b =
        block_index[static_cast<std::size_t>(bx) +
                    static_cast<std::size_t>(block_dims[0]) *
                        (static_cast<std::size_t>(by) +
                         static_cast<std::size_t>(block_dims[1]) * static_cast<std::size_t>(bz))];
    return b < 0 ? kNoSlot : static_cast<std::size_t>(b) * kBlockNodes;
  }
  // The slot of node (i, j, k) inside the lattice, kNoSlot where its block
  // is not held (NodeLattice::slot_of without the periodic wrap).
  OBSCURA_HOST_DEVICE std::size_t node_slot(int i, int j, int k) const {
    const std::size_t first = block_first_slot(i / kBlock, j / kBlock, k / kBlock);
    return first == kNoSlot
               ? kNoSlot
               : first + static_cast<std::size_t>(i % kBlock +
                                                  kBlock * (j % kBlock + kBlock * (k % kBlock)));
  }
};

// Whether lattice point `node` lies outside the medium's box `domain` (a rim
// node of a lattice laid on a grid), and the box's point nearest it, `face`.
// The rim node serves only the half cell inside the box, between the face and
// its inner neighbour 2 face − node: a quantity f that is linear there (the
// sun's optical depth at a cloud's face, where it is zero just outside) is
// read by the trilinear interpolation exactly when the rim node holds
// 2 f(face) − f(2 face − node), not f(node) itself
// (docs/physics.md, "The sun's depth at a cloud's face").
OBSCURA_HOST_DEVICE inline bool rim_face(const BBox3& domain, const Vec3& node, Vec3& face) {
  face = Vec3(node.x < domain.lo.x ? domain.lo.x : (node.x > domain.hi.x ? domain.hi.x : node.x),
              node.y < domain.lo.y ? domain.lo.y : (node.y > domain.hi.y ? domain.hi.y : node.y),
              node.z < domain.lo.z ? domain.lo.z : (node.z > domain.hi.z ? domain.hi.z : node.z));
  return face.x != node.x || face.y != node.y || face.z != node.z;
}

// The layout both compilers must agree on (tests/render/lattice/
// lattice_view_test.cpp repeats these, and gpu/check compares them with what
// device code sees).
static_assert(std::is_trivially_copyable_v<LatticeView> && std::is_standard_layout_v<LatticeView>);
static_assert(sizeof(Vec3) == 24 && sizeof(Mat3) == 72 && sizeof(BBox3) == 48);
static_assert(offsetof(LatticeView, to_lattice_axes) == 24 &&
              offsetof(LatticeView, spacing_m) == 96 && offsetof(LatticeView, dims) == 104 &&
              offsetof(LatticeView, block_dims) == 116 &&
              offsetof(LatticeView, block_index) == 128 && offsetof(LatticeView, blocks) == 136 &&
              offsetof(LatticeView, occupied) == 144 && offsetof(LatticeView, zero_slot) == 152 &&
              offsetof(LatticeView, domain) == 160 && sizeof(LatticeView) == 208);
static_assert(sizeof(std::array<int, 3>) == 12);

}  // namespace obscura
