#pragma once
// The nodes the radiance cache keeps its values at: a regular lattice, node
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

#include "obscura/core/mat3.h"
#include "obscura/core/vec3.h"
#include "obscura/medium/medium.h"

namespace obscura {

class CacheLattice {
 public:
  static constexpr int kBlock = 8;  // nodes per block side
  static constexpr int kBlockNodes = kBlock * kBlock * kBlock;

  // A lattice over `medium` at spacing `spacing_m` (0: the medium's voxel
  // size, or its largest extent / 32); `period_m` > 0 makes x and y periodic
  // with that period (rounded to whole spacings). Only blocks where the
  // medium may be non-zero (within one spacing) are allocated. Throws
  // InputError naming "render/radiance_cache/voxel_m" when the lattice
  // would need more than `max_nodes` nodes.
  CacheLattice(const Medium& medium, double spacing_m, double period_m, std::size_t max_nodes);

  double spacing_m() const { return h_; }
  const std::array<int, 3>& dims() const { return dims_; }
  bool periodic() const { return periodic_; }
  std::size_t block_count() const { return blocks_.size(); }
  // Node slots: block b holds slots [b kBlockNodes, (b + 1) kBlockNodes).
  std::size_t slot_count() const { return blocks_.size() * kBlockNodes; }
  // The world position of a slot's node, and whether that node is inside the
  // lattice (the last block along an axis may reach past it).
  Vec3 slot_position(std::size_t slot) const;
  bool slot_inside(std::size_t slot) const;

  // The 8 nodes around world point p and their trilinear weights; corners in
  // blocks that do not exist get slot kNoSlot (their values count as zero).
  // False when p lies outside the lattice.
  static constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);
  bool corners(const Vec3& p, std::array<std::size_t, 8>& slot, std::array<double, 8>& w) const;

  // The slot of node (i, j, k) (wrapped when periodic), kNoSlot if absent.
  std::size_t slot_of(int i, int j, int k) const;
  // Lattice coordinates of a world point (node units).
  Vec3 to_lattice(const Vec3& p) const { return rotation_t_ * (p - origin_) / h_; }
  const Mat3& rotation() const { return rotation_; }

 private:
  void allocate_blocks(const Medium& medium);

  Vec3 origin_;
  Mat3 rotation_ = Mat3::identity(), rotation_t_ = Mat3::identity();
  double h_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::array<int, 3> block_dims_{1, 1, 1};
  bool periodic_ = false;
  std::vector<std::int32_t> block_index_;   // per block of the lattice: its slot block, or −1
  std::vector<std::array<int, 3>> blocks_;  // per allocated block: its block coordinates
};

}  // namespace obscura
