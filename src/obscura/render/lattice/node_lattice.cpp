#include "obscura/render/lattice/node_lattice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/core/fast_floor.h"
#include "obscura/core/host_device.h"

namespace obscura {
namespace {

// Nodes along one axis: from (−½ h) to past length + ½ h.
int nodes_along(double length_m, double h) {
  return std::max(2, static_cast<int>(std::ceil(length_m / h - 1e-9)) + 2);
}

// Nodes along one axis from 0 to past length, one on each end.
int nodes_on(double length_m, double h) {
  return std::max(2, static_cast<int>(std::ceil(length_m / h - 1e-9)) + 1);
}

int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

}  // namespace

NodeLattice::NodeLattice(const Medium& medium, double spacing_m, double period_m,
                         std::size_t max_nodes) {
  const BBox3 b = medium.bounds();
  const std::optional<GridFrame> frame = medium.grid_frame();
  Vec3 lengths = b.extent();
  Vec3 corner = b.lo;
  if (period_m > 0.0) {
    periodic_ = true;
    h_ = periodic_spacing_m(lengths.z, spacing_m);
    const int per = std::max(kMinPeriodNodes, static_cast<int>(std::lround(period_m / h_)));
    h_ = period_m / per;
    // Nodes on the slab's faces: its σs steps there, at a node, where the
    // splats' normalisation (two-point Gauss per lattice interval) is exact.
    origin_ = Vec3(0.0, 0.0, b.lo.z);
    dims_ = {per, per, nodes_on(lengths.z, h_)};
    constexpr double kInf = std::numeric_limits<double>::infinity();
    medium_support_ = BBox3(Vec3(-kInf, -kInf, 0.0), Vec3(kInf, kInf, lengths.z / h_));
  } else {
    if (frame) {
      rotation_ = frame->placement.rotation;
      corner = frame->placement.origin_m;
      const double v = frame->placement.voxel_size_m;
      lengths = Vec3(frame->dims.nx * v, frame->dims.ny * v, frame->dims.nz * v);
      h_ = spacing_m > 0 ? spacing_m : v;
      // Node 1 at ½ h inside the minimum corner: at a grid's own voxel size,
      // the voxel centres.
      origin_ = corner + rotation_ * Vec3(-0.5 * h_, -0.5 * h_, -0.5 * h_);
      dims_ = {nodes_along(lengths.x, h_), nodes_along(lengths.y, h_), nodes_along(lengths.z, h_)};
      medium_support_ = BBox3(Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5) + lengths / h_);
    } else {
      // Other media (boxes): nodes on the box's minimum faces, and on the
      // others where the extent is a whole number of spacings (a cube).
      h_ = spacing_m > 0 ? spacing_m : std::max({lengths.x, lengths.y, lengths.z}) / 32.0;
      origin_ = corner;
      dims_ = {nodes_on(lengths.x, h_), nodes_on(lengths.y, h_), nodes_on(lengths.z, h_)};
      medium_support_ = BBox3(Vec3(0.0, 0.0, 0.0), lengths / h_);
    }
  }
  if (!(h_ > 0.0 && std::isfinite(h_)))
    throw InputError("", "render/radiance_cache/voxel_m",
                     "the medium has no extent to lay a lattice over");
  rotation_t_ = rotation_.transposed();
  const double nodes = static_cast<double>(dims_[0]) * dims_[1] * dims_[2];
  if (nodes > static_cast<double>(max_nodes))
    throw InputError("", "render/radiance_cache/voxel_m",
                     fmt::format("a lattice at {:.4g} m would have {:.3g} nodes (at most {:.3g}): "
                                 "give a larger voxel_m",
                                 h_, nodes, static_cast<double>(max_nodes)));
  allocate_blocks(medium);
}

void NodeLattice::allocate_blocks(const Medium& medium) {
  for (int a = 0; a < 3; ++a) block_dims_[a] = (dims_[a] + kBlock - 1) / kBlock;
  block_index_.assign(static_cast<std::size_t>(block_dims_[0]) * block_dims_[1] * block_dims_[2],
                      -1);
  for (int bz = 0; bz < block_dims_[2]; ++bz)
    for (int by = 0; by < block_dims_[1]; ++by)
      for (int bx = 0; bx < block_dims_[0]; ++bx) {
        // The block's nodes and one more each side (a node is needed wherever
        // a neighbouring cell holds medium), as a world box.
        const std::array<int, 3> b = {bx, by, bz};
        BBox3 box;
        for (int c = 0; c < 8; ++c) {
          Vec3 node;
          for (int a = 0; a < 3; ++a)
            node[a] = (c >> a & 1) ? std::min(b[a] * kBlock + kBlock, dims_[a]) : b[a] * kBlock - 1;
          box.expand(origin_ + rotation_ * (node * h_));
        }
        if (!periodic_ && !medium.may_be_nonzero(box)) continue;
        block_index_[static_cast<std::size_t>(bx) +
                     static_cast<std::size_t>(block_dims_[0]) *
                         (static_cast<std::size_t>(by) +
                          static_cast<std::size_t>(block_dims_[1]) * bz)] =
            static_cast<std::int32_t>(blocks_.size());
        blocks_.push_back(b);
      }
}

LatticeView NodeLattice::view() const {
  LatticeView v;
  v.origin_m = origin_;
  v.to_lattice_axes = rotation_t_;
  v.spacing_m = h_;
  for (int a = 0; a < 3; ++a) {
    v.dims[a] = dims_[a];
    v.block_dims[a] = block_dims_[a];
  }
  v.block_index = block_index_.data();
  v.blocks = blocks_.data();
  v.zero_slot = slot_count();
  return v;
}

// Inlined: corners calls it six times a point.
OBSCURA_ALWAYS_INLINE inline bool NodeLattice::axis_share(int a, int i, AxisShare& share) const {
  if (periodic_ && a < 2) i = wrap(i, dims_[a]);
  if (i < 0 || i >= dims_[a]) return false;
  const std::size_t block_stride[3] = {
      1, static_cast<std::size_t>(block_dims_[0]),
      static_cast<std::size_t>(block_dims_[0]) * static_cast<std::size_t>(block_dims_[1])};
  constexpr std::size_t kPlaceStride[3] = {1, kBlock, kBlock * kBlock};
  const auto node = static_cast<std::size_t>(i);
  share.block = node / kBlock * block_stride[a];
  share.place = node % kBlock * kPlaceStride[a];
  return true;
}

OBSCURA_ALWAYS_INLINE inline std::size_t NodeLattice::slot_from(const AxisShare& x,
                                                                const AxisShare& y,
                                                                const AxisShare& z) const {
  const std::int32_t b = block_index_[x.block + y.block + z.block];
  if (b < 0) return kNoSlot;
  return static_cast<std::size_t>(b) * kBlockNodes + x.place + y.place + z.place;
}

std::size_t NodeLattice::slot_of(int i, int j, int k) const {
  AxisShare x, y, z;
  if (!axis_share(0, i, x) || !axis_share(1, j, y) || !axis_share(2, k, z)) return kNoSlot;
  return slot_from(x, y, z);
}

std::array<int, 3> NodeLattice::slot_node(std::size_t slot) const {
  const std::array<int, 3>& b = blocks_[slot / kBlockNodes];
  const int local = static_cast<int>(slot % kBlockNodes);
  return {b[0] * kBlock + local % kBlock, b[1] * kBlock + (local / kBlock) % kBlock,
          b[2] * kBlock + local / (kBlock * kBlock)};
}

Vec3 NodeLattice::slot_position(std::size_t slot) const {
  const std::array<int, 3> n = slot_node(slot);
  return origin_ + rotation_ * (Vec3(n[0], n[1], n[2]) * h_);
}

bool NodeLattice::slot_inside(std::size_t slot) const {
  const std::array<int, 3> n = slot_node(slot);
  return n[0] < dims_[0] && n[1] < dims_[1] && n[2] < dims_[2];
}

bool NodeLattice::corners(const Vec3& p, std::array<std::size_t, 8>& slot,
                          std::array<double, 8>& w) const {
  Vec3 u = to_lattice(p);
  std::array<int, 3> i0;
  std::array<double, 3> f;
  for (int a = 0; a < 3; ++a) {
    const bool wraps = periodic_ && a < 2;
    // A point on the lattice's first or last node plane, as a cloud's face
    // that lies on nodes, may come out of to_lattice a rounding error
    // outside it: it is on the plane (a camera ray's entry into a box cloud
    // read no light there; docs/validation.md).
    constexpr double kOnPlane = 1e-9;
    if (!wraps && u[a] < 0.0 && u[a] > -kOnPlane) u[a] = 0.0;
    if (!wraps && u[a] > dims_[a] - 1 && u[a] < dims_[a] - 1 + kOnPlane) u[a] = dims_[a] - 1;
    const double fl = fast_floor(u[a]);
    i0[a] = static_cast<int>(fl);
    f[a] = u[a] - fl;
    if (!wraps && (u[a] < 0.0 || u[a] > dims_[a] - 1)) return false;
    if (!wraps && i0[a] == dims_[a] - 1) {  // on the last node
      i0[a] -= 1;
      f[a] = 1.0;
    }
  }
  // Each axis's two nodes wrapped and split into their shares of the slot
  // once, not per corner through slot_of: the same slots and weights, in
  // about a third of the instructions (the generic march reads the lattice
  // at every point; docs/performance.md).
  AxisShare share[3][2];
  bool on[3][2];
  double weight[3][2];
  for (int a = 0; a < 3; ++a) {
    weight[a][0] = 1 - f[a];
    weight[a][1] = f[a];
    for (int b = 0; b < 2; ++b) on[a][b] = axis_share(a, i0[a] + b, share[a][b]);
  }
  for (int c = 0; c < 8; ++c) {
    const int x = c & 1, y = c >> 1 & 1, z = c >> 2 & 1;
    w[c] = weight[0][x] * weight[1][y] * weight[2][z];
    slot[c] = on[0][x] && on[1][y] && on[2][z] ? slot_from(share[0][x], share[1][y], share[2][z])
                                               : kNoSlot;
  }
  return true;
}

}  // namespace obscura
