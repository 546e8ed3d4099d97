#include "obscura/render/lattice/lattice_volume.h"

#include <algorithm>
#include <cmath>

#include "obscura/core/check.h"
#include "obscura/core/memory_limit.h"
#include "obscura/core/parallel.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

// Lattices up to this many nodes are laid out (only occupied blocks are stored).
constexpr double kMaxLatticeNodes = 4e9;

}  // namespace

const VoxelGrid* LatticeVolume::aligned_grid(const Medium& medium, const NodeLattice& lattice) {
  const std::optional<GridFrame> frame = medium.grid_frame();
  if (!frame || !frame->trilinear || !frame->voxels || lattice.periodic()) return nullptr;
  const GridPlacement& p = frame->placement;
  const double h = lattice.spacing_m();
  if (!(std::abs(p.voxel_size_m - h) <= 1e-12 * h)) return nullptr;
  // Node (1, 1, 1) on voxel (0, 0, 0)'s centre, one rim node each side.
  const Vec3 node1 = lattice.origin() + lattice.rotation() * Vec3(h, h, h);
  if (length(node1 - p.index_to_world(Vec3(0, 0, 0))) > 1e-9 * h * (1.0 + length(p.origin_m)))
    return nullptr;
  const GridDims& d = frame->dims;
  const std::array<int, 3>& n = lattice.dims();
  if (n[0] != d.nx + 2 || n[1] != d.ny + 2 || n[2] != d.nz + 2) return nullptr;
  return frame->voxels;
}

double LatticeVolume::bytes_needed(const NodeLattice& lattice, int nodes, int stride) {
  const double slots = static_cast<double>(lattice.slot_count()) + 1.0;
  return slots * (static_cast<double>(nodes) * stride * sizeof(float) + 1.0);
}

LatticeVolume::LatticeVolume(const NodeLattice& lattice, const std::vector<SpectralLerp>& lerps,
                             int stride, const VoxelGrid* voxels, int threads,
                             const std::string& field)
    : lattice_(&lattice), stride_(stride), has_medium_(voxels != nullptr) {
  OBSCURA_CHECK(stride >= record::kMediumStride);
  check_memory(
      static_cast<std::uint64_t>(bytes_needed(lattice, static_cast<int>(lerps.size()), stride)), "",
      field, "the lattice march's records");
  const std::size_t slots = lattice.slot_count() + 1;  // and the zero slot
  records_.assign(lerps.size(), std::vector<float>(slots * static_cast<std::size_t>(stride), 0.0f));
  occupied_.assign(slots, 0);
  if (!voxels) return;
  const VoxelGrid& grid = *voxels;
  const GridDims& d = grid.dims();
  domain_ = BBox3(Vec3(0.5, 0.5, 0.5), Vec3(d.nx + 0.5, d.ny + 0.5, d.nz + 0.5));
  // The channels through pointers found once per frame, not through the
  // grid's accessors per node and lerp (half the records' instructions:
  // docs/performance.md).
  const GridChannels ch(grid);
  const std::size_t ns = ch.sigma_a.size();
  // Per lerp its two samples' channels and weights, so that a node reads no
  // vector of pointers (13 % of the records' instructions).
  struct LerpChannels {
    const float *sigma_a0, *sigma_a1, *sigma_s0, *sigma_s1, *g0, *g1;
    double w0, w1;
  };
  std::vector<LerpChannels> channels;
  for (const SpectralLerp& l : lerps) {
    const auto s0 = static_cast<std::size_t>(l.sample0), s1 = static_cast<std::size_t>(l.sample1);
    channels.push_back({ch.sigma_a[s0], ch.sigma_a[s1], ch.sigma_s[s0], ch.sigma_s[s1], ch.g[s0],
                        ch.g[s1], 1.0 - l.frac, l.frac});
  }
  const std::array<int, 3>& dims = lattice.dims();
  parallel_for(lattice.block_count(), threads, [&](std::size_t block) {
    const std::array<int, 3> first = lattice.block_first_node(block);
    std::size_t slot = block * NodeLattice::kBlockNodes;
    for (int k = first[2]; k < first[2] + NodeLattice::kBlock; ++k)
      for (int j = first[1]; j < first[1] + NodeLattice::kBlock; ++j)
        for (int i = first[0]; i < first[0] + NodeLattice::kBlock; ++i, ++slot) {
          if (i >= dims[0] || j >= dims[1] || k >= dims[2]) continue;
          // Node i holds voxel i − 1, the rim nodes the edge voxels.
          const std::size_t v =
              grid.index(std::clamp(i - 1, 0, d.nx - 1), std::clamp(j - 1, 0, d.ny - 1),
                         std::clamp(k - 1, 0, d.nz - 1));
          bool occupied = false;
          for (std::size_t s = 0; s < ns; ++s)
            occupied = occupied || ch.sigma_a[s][v] != 0.0f || ch.sigma_s[s][v] != 0.0f;
          occupied_[slot] = occupied ? 1 : 0;
          for (std::size_t u = 0; u < channels.size(); ++u) {
            const LerpChannels& c = channels[u];
            const double ss0 = c.sigma_s0[v], ss1 = c.sigma_s1[v];
            float* r = record(static_cast<int>(u), slot);
            r[record::kSigmaA] = static_cast<float>(c.w0 * c.sigma_a0[v] + c.w1 * c.sigma_a1[v]);
            r[record::kSigmaS] = static_cast<float>(c.w0 * ss0 + c.w1 * ss1);
            r[record::kTemperature] = ch.temperature[v];
            r[record::kSigmaSG] = static_cast<float>(c.w0 * ss0 * c.g0[v] + c.w1 * ss1 * c.g1[v]);
          }
        }
  });
}

LatticeView LatticeVolume::view() const {
  LatticeView v = lattice_->view();
  v.occupied = occupied_.data();
  v.zero_slot = zero_slot();
  v.domain = domain_;
  return v;
}

std::size_t LatticeVolume::memory_bytes() const {
  std::size_t n = occupied_.size();
  for (const auto& r : records_) n += r.size() * sizeof(float);
  return n;
}

GridRecords grid_records(const Medium& medium, const std::vector<SpectralLerp>& lerps, int stride,
                         int threads) {
  GridRecords out;
  const std::optional<GridFrame> frame = medium.grid_frame();
  if (!frame || !frame->voxels) return out;  // not one grid
  auto lattice =
      std::make_unique<NodeLattice>(medium, 0.0, 0.0, static_cast<std::size_t>(kMaxLatticeNodes));
  const VoxelGrid* grid = LatticeVolume::aligned_grid(medium, *lattice);
  if (!grid) return out;
  out.volume = std::make_unique<LatticeVolume>(*lattice, lerps, stride, grid, threads, "clouds");
  out.lattice = std::move(lattice);
  return out;
}

}  // namespace obscura
