#include "obscura/io/vdb_density_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <tuple>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_keyframe_placement.h"
#include "obscura/io/vdb_open.h"

namespace obscura {
namespace {

using vdb_format::DenseXYZ;

std::string grid_names(openvdb::io::File& f) {
  std::vector<std::string> names;
  for (auto it = f.beginName(); it != f.endName(); ++it) names.push_back(*it);
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

// The header of float grid `name` (no voxel data read), checked.
openvdb::GridBase::Ptr float_grid_header(openvdb::io::File& f, const std::string& name,
                                         const std::string& file, const char* key) {
  if (!f.hasGrid(name))
    throw InputError(file, name,
                     fmt::format("no grid of that name (the file's grids: {}); the scene's "
                                 "\"{}\" names the grid to read",
                                 grid_names(f), key));
  openvdb::GridBase::Ptr h;
  try {
    h = f.readGridMetadata(name);
  } catch (const openvdb::Exception& e) {
    throw InputError(file, name, fmt::format("cannot read grid header ({})", e.what()));
  }
  if (!h->isType<openvdb::FloatGrid>())
    throw InputError(file, name,
                     fmt::format("grid holds {} values, expected a float grid (a scalar "
                                 "density or temperature)",
                                 h->valueType()));
  if (h->getGridClass() == openvdb::GRID_LEVEL_SET)
    throw InputError(file, name,
                     "grid is a level set (a signed distance to a surface), not a density or "
                     "temperature");
  return h;
}

openvdb::FloatGrid::Ptr read_float_grid(openvdb::io::File& f, const std::string& name,
                                        const std::string& file) {
  try {
    return openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(name));
  } catch (const openvdb::Exception& e) {
    throw InputError(file, name, fmt::format("cannot read grid ({})", e.what()));
  }
}

// The file's density (and temperature) grids, read and checked.
struct DensityGrids {
  std::string file;
  openvdb::FloatGrid::Ptr density, temperature;  // temperature: null unless asked for
  GridPlacement index_placement;                 // OpenVDB's index space in metres
};

DensityGrids read_grids(const std::filesystem::path& path, const std::string& density_grid,
                        const std::string& temperature_grid) {
  DensityGrids g;
  g.file = path.string();
  const std::string& file = g.file;
  const std::unique_ptr<openvdb::io::File> opened = vdb_format::open_checked_vdb_file(path);
  openvdb::io::File& f = *opened;
  const openvdb::GridBase::Ptr density_header =
      float_grid_header(f, density_grid, file, "density_grid");
  if (!temperature_grid.empty()) {
    const openvdb::GridBase::Ptr temperature_header =
        float_grid_header(f, temperature_grid, file, "temperature_grid");
    if (!(temperature_header->constTransform() == density_header->constTransform()))
      throw InputError(file, temperature_grid,
                       fmt::format("grid transform differs from the density grid '{}''s; "
                                   "both must lie on the same voxels",
                                   density_grid));
  }
  g.index_placement =
      vdb_format::transform_to_placement(density_header->constTransform(), file, density_grid);
  g.density = read_float_grid(f, density_grid, file);
  if (g.density->background() != 0.0f)
    throw InputError(file, density_grid,
                     fmt::format("background value {} (the density outside the active voxels) "
                                 "must be 0: a cloud ends where its active voxels do",
                                 g.density->background()));
  if (!temperature_grid.empty()) g.temperature = read_float_grid(f, temperature_grid, file);
  f.close();
  return g;
}

// The dense arrays of `box` (inclusive OpenVDB index bounds); `empty`: the
// density grid has no active voxel.
VdbDensityVolume dense_volume(const DensityGrids& g, const openvdb::CoordBBox& box, bool empty) {
  VdbDensityVolume v;
  v.empty = empty;
  const openvdb::Coord lo = box.min(), extent = box.dim();
  v.dims = {extent.x(), extent.y(), extent.z()};
  for (int a = 0; a < 3; ++a) v.index_min[a] = lo[a];
  // Voxel (0, 0, 0) of the dense arrays is OpenVDB's voxel `lo`.
  v.placement = g.index_placement;
  v.placement.origin_m =
      g.index_placement.origin_m +
      g.index_placement.rotation * (Vec3(lo.x(), lo.y(), lo.z()) * g.index_placement.voxel_size_m);
  v.density.assign(v.dims.count(), 0.0f);
  if (!empty) {
    DenseXYZ dense(box, v.density.data());
    openvdb::tools::copyToDense(*g.density, dense);
  }
  if (g.temperature) {
    v.temperature.assign(v.dims.count(), 0.0f);
    DenseXYZ dense(box, v.temperature.data());
    openvdb::tools::copyToDense(*g.temperature, dense);
  }
  return v;
}

// Checks the dense arrays of `voxels` voxels against the memory limit.
void check_dense_memory(const DensityGrids& g, const std::string& density_grid, double voxels,
                        const std::string& what) {
  const int grids = g.temperature ? 2 : 1;
  const double bytes = voxels * grids * 4.0;
  check_memory(bytes < 1.8e19 ? static_cast<std::uint64_t>(bytes) : UINT64_MAX, g.file,
               density_grid,
               fmt::format("{} as {} dense float grid{}", what, grids, grids > 1 ? "s" : ""));
}

// The leaf (8³ voxels) holding voxel c.
std::array<int, 3> leaf_key(const openvdb::Coord& c) {
  return {c.x() >> 3, c.y() >> 3, c.z() >> 3};
}

// Boxes around the clusters of active voxels (see read_vdb_density_parts), or
// nothing when the active voxels span more than `max_leaves` leaves.
std::vector<openvdb::CoordBBox> cluster_boxes(const openvdb::FloatTree& tree,
                                              std::size_t max_leaves) {
  // Per active leaf, the box of its active voxels (tiles' parts included).
  std::map<std::array<int, 3>, openvdb::CoordBBox> leaves;
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
    if (leaf->onVoxelCount() == 0) continue;
    openvdb::CoordBBox active;
    leaf->evalActiveBoundingBox(active, true);
    leaves[leaf_key(leaf->origin())].expand(active);
    if (leaves.size() > max_leaves) return {};
  }
  for (auto it = tree.cbeginValueOn(); it; ++it) {
    if (!it.isTileValue()) continue;
    openvdb::CoordBBox tile;
    it.getBoundingBox(tile);
    const std::array<int, 3> lo = leaf_key(tile.min()), hi = leaf_key(tile.max());
    const double count = (hi[0] - lo[0] + 1.0) * (hi[1] - lo[1] + 1.0) * (hi[2] - lo[2] + 1.0);
    if (static_cast<double>(leaves.size()) + count > static_cast<double>(max_leaves)) return {};
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const openvdb::CoordBBox leaf_box(openvdb::Coord(8 * x, 8 * y, 8 * z),
                                            openvdb::Coord(8 * x + 7, 8 * y + 7, 8 * z + 7));
          leaves[{x, y, z}].expand(
              openvdb::CoordBBox(openvdb::Coord::maxComponent(tile.min(), leaf_box.min()),
                                 openvdb::Coord::minComponent(tile.max(), leaf_box.max())));
        }
  }
  // Leaves that touch (26 neighbours) form one cluster: union–find over
  // the leaves in key order, so the result does not depend on the tree's.
  std::vector<std::array<int, 3>> keys;
  std::map<std::array<int, 3>, std::size_t> index;
  for (const auto& [key, box] : leaves) {
    index[key] = keys.size();
    keys.push_back(key);
  }
  std::vector<std::size_t> parent(keys.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < keys.size(); ++i)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto n = index.find({keys[i][0] + dx, keys[i][1] + dy, keys[i][2] + dz});
          if (n == index.end()) continue;
          const std::size_t a = root(i), b = root(n->second);
          if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
  std::map<std::size_t, openvdb::CoordBBox> clusters;  // by root
  for (std::size_t i = 0; i < keys.size(); ++i) clusters[root(i)].expand(leaves[keys[i]]);
  // One voxel of background around each, then merge boxes that overlap.
  std::vector<openvdb::CoordBBox> boxes;
  for (auto& [r, box] : clusters) {
    box.expand(1);
    boxes.push_back(box);
  }
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < boxes.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < boxes.size() && !merged; ++j)
        if (boxes[i].hasOverlap(boxes[j])) {
          boxes[i].expand(boxes[j]);
          boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
  }
  std::sort(boxes.begin(), boxes.end(),
            [](const openvdb::CoordBBox& a, const openvdb::CoordBBox& b) {
              const openvdb::Coord p = a.min(), q = b.min();
              return std::tuple(p.z(), p.y(), p.x()) < std::tuple(q.z(), q.y(), q.x());
            });
  return boxes;
}

// The density grid's active bounding box, or one voxel at index 0 when it has none.
openvdb::CoordBBox active_box(const openvdb::FloatGrid& density, bool& empty) {
  openvdb::CoordBBox box = density.evalActiveVoxelBoundingBox();
  empty = box.empty();
  return empty ? openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0)) : box;
}

VdbDensityVolume whole_box(const DensityGrids& g, const openvdb::CoordBBox& box, bool empty,
                           const std::string& density_grid) {
  const openvdb::Coord extent = box.dim();
  check_dense_memory(g, density_grid, static_cast<double>(extent.x()) * extent.y() * extent.z(),
                     fmt::format("the active bounding box of {}x{}x{} voxels", extent.x(),
                                 extent.y(), extent.z()));
  return dense_volume(g, box, empty);
}

}  // namespace

VdbDensityVolume read_vdb_density(const std::filesystem::path& path,
                                  const std::string& density_grid,
                                  const std::string& temperature_grid) {
  const DensityGrids g = read_grids(path, density_grid, temperature_grid);
  bool empty = false;
  const openvdb::CoordBBox box = active_box(*g.density, empty);
  return whole_box(g, box, empty, density_grid);
}

std::vector<VdbDensityVolume> read_vdb_density_parts(const std::filesystem::path& path,
                                                     const std::string& density_grid,
                                                     const std::string& temperature_grid) {
  const DensityGrids g = read_grids(path, density_grid, temperature_grid);
  bool empty = false;
  const openvdb::CoordBBox box = active_box(*g.density, empty);
  std::vector<VdbDensityVolume> parts;
  if (!empty) {
    // Beyond a million leaves (5·10⁸ voxels) the clusters are not worth their
    // map, nor beyond a 256th of the memory limit (a map entry takes under
    // 256 bytes): then the one box, whose memory is checked.
    const std::size_t max_leaves =
        std::min<std::uint64_t>(std::uint64_t{1} << 20, memory_limit_bytes() / 256);
    const std::vector<openvdb::CoordBBox> boxes = cluster_boxes(g.density->tree(), max_leaves);
    double voxels = 0.0;
    for (const openvdb::CoordBBox& b : boxes) voxels += static_cast<double>(b.volume());
    if (boxes.size() > 1 && boxes.size() <= static_cast<std::size_t>(kMaxVdbDensityParts) &&
        2.0 * voxels < static_cast<double>(box.volume())) {
      check_dense_memory(g, density_grid, voxels,
                         fmt::format("the {} clusters of active voxels ({} voxels in all)",
                                     boxes.size(), static_cast<std::uint64_t>(voxels)));
      for (const openvdb::CoordBBox& b : boxes) parts.push_back(dense_volume(g, b, false));
      return parts;
    }
  }
  parts.push_back(whole_box(g, box, empty, density_grid));
  return parts;
}

}  // namespace obscura
