#pragma once
// The nodes at which per-frame values over a medium are kept (the radiance
// cache's light, the lattice march's records: lattice_march.h): a regular lattice, node
// (i, j, k) at origin + R h (i, j, k) (R the rotation of the cloud's grid, h
// the spacing), stored in blocks of 8³ nodes that exist only where the medium
// may be non-zero. Values between nodes are trilinear. Aligned with a grid
// cloud at its own voxel size, the nodes are the voxel centres (plus one rim
// node each side), so the cache's fields are cubic along a ray inside each of
// the medium's cells, like the medium itself. Optionally periodic in x and y
// (a laterally infinite slab): node indices wrap.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/mat3.h"
#include "obscura/core/vec3.h"
#include "obscura/medium/medium.h"
#include "obscura/render/lattice/lattice_view.h"

namespace obscura {

class NodeLattice {
 public:
  static constexpr int kBlock = LatticeView::kBlock;  // nodes per block side
  static constexpr int kBlockNodes = kBlock * kBlock * kBlock;

  // A lattice over `medium` at spacing `spacing_m` (0: the medium's voxel
  // size, or its largest extent / 32); `period_m` > 0 makes x and y periodic
  // with that period (rounded to whole spacings). Only blocks where the
  // medium may be non-zero (within one spacing) are allocated. Throws
  // InputError naming "render/radiance_cache/voxel_m" when the lattice
  // would need more than `max_nodes` nodes.
  NodeLattice(const Medium& medium, double spacing_m, double period_m, std::size_t max_nodes);

  // A periodic lattice wraps over this many nodes at least (a shorter period
  // is widened to it).
  static constexpr int kMinPeriodNodes = 4;
  // The spacing of a periodic lattice over a slab `thickness_m` thick:
  // `spacing_m` when > 0, else 32 intervals across the slab.
  static double periodic_spacing_m(double thickness_m, double spacing_m) {
    return spacing_m > 0 ? spacing_m : thickness_m / 32.0;
  }

  double spacing_m() const { return h_; }
  const std::array<int, 3>& dims() const { return dims_; }
  bool periodic() const { return periodic_; }
  std::size_t block_count() const { return blocks_.size(); }
  // Node slots: block b holds slots [b kBlockNodes, (b + 1) kBlockNodes).
  std::size_t slot_count() const { return blocks_.size() * kBlockNodes; }
  // The world position of a slot's node, and whether that node is inside the
  // lattice (the last block along an axis may reach past it).
  Vec3 slot_position(std::size_t slot) const;
  // The node (i, j, k) a slot holds, and the first node of a held block
  // (whose slot b kBlockNodes + i + 8 j + 64 k holds that node plus (i, j, k)).
  std::array<int, 3> slot_node(std::size_t slot) const;
  std::array<int, 3> block_first_node(std::size_t block) const {
    const std::array<int, 3>& b = blocks_[block];
    return {b[0] * kBlock, b[1] * kBlock, b[2] * kBlock};
  }
  bool slot_inside(std::size_t slot) const;

  // The 8 nodes around world point p and their trilinear weights; corners in
  // blocks that do not exist get slot kNoSlot (their values count as zero).
  // False when p lies outside the lattice (a point within 10⁻⁹ of a spacing
  // outside its first or last node plane, as a rounding error puts a point
  // on a box cloud's face, is on the plane).
  static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
  bool corners(const Vec3& p, std::array<std::size_t, 8>& slot, std::array<double, 8>& w) const;

  // The slot of node (i, j, k) (wrapped when periodic), kNoSlot if absent.
  std::size_t slot_of(int i, int j, int k) const;
  // Blocks per axis, and the first slot of block (bx, by, bz) (kNoSlot if
  // absent); node (i, j, k) of a held block is at that slot plus
  // (i mod 8) + 8 (j mod 8) + 64 (k mod 8).
  const std::array<int, 3>& block_dims() const { return block_dims_; }
  std::size_t block_first_slot(int bx, int by, int bz) const {
    const std::int32_t b =
        block_index_[static_cast<std::size_t>(bx) +
                     static_cast<std::size_t>(block_dims_[0]) *
                         (static_cast<std::size_t>(by) +
                          static_cast<std::size_t>(block_dims_[1]) * static_cast<std::size_t>(bz))];
    return b < 0 ? kNoSlot : static_cast<std::size_t>(b) * kBlockNodes;
  }
  // The box outside which the medium is zero, in lattice coordinates (node
  // units): the medium's box (a grid cloud's own, rotated with it), without
  // bounds across a periodic lattice's x and y. Its faces are where σs may
  // step to zero between two nodes.
  const BBox3& medium_support() const { return medium_support_; }
  // The origin's world position (node (0, 0, 0)).
  const Vec3& origin() const { return origin_; }
  // Lattice coordinates of a world point (node units).
  Vec3 to_lattice(const Vec3& p) const { return rotation_t_ * (p - origin_) / h_; }
  // A world direction in node units per metre.
  Vec3 to_lattice_direction(const Vec3& d) const { return rotation_t_ * d / h_; }
  const Mat3& rotation() const { return rotation_; }
  // The lattice's part of a LatticeView (lattice_view.h): its placement and
  // blocks, pointing into this lattice (valid while it lives); the occupancy
  // and domain are the LatticeVolume's.
  LatticeView view() const;

 private:
  // Node index i along axis a (wrapped when periodic) as its share of the
  // block's index and of the place in the block; false off the lattice.
  // slot_of and corners (which finds each axis's two nodes once) both build
  // a slot from these shares with slot_from.
  struct AxisShare {
    std::size_t block = 0, place = 0;
  };
  bool axis_share(int a, int i, AxisShare& share) const;
  std::size_t slot_from(const AxisShare& x, const AxisShare& y, const AxisShare& z) const;
  void allocate_blocks(const Medium& medium);

  Vec3 origin_;
  BBox3 medium_support_;
  Mat3 rotation_ = Mat3::identity(), rotation_t_ = Mat3::identity();
  double h_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::array<int, 3> block_dims_{1, 1, 1};
  bool periodic_ = false;
  std::vector<std::int32_t> block_index_;   // per block of the lattice: its slot block, or −1
  std::vector<std::array<int, 3>> blocks_;  // per allocated block: its block coordinates
};

}  // namespace obscura
