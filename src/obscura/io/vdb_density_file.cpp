#include "obscura/io/vdb_density_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <cstdint>

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

}  // namespace

VdbDensityVolume read_vdb_density(const std::filesystem::path& path,
                                  const std::string& density_grid,
                                  const std::string& temperature_grid) {
  const std::string file = path.string();
  const std::unique_ptr<openvdb::io::File> opened = vdb_format::open_checked_vdb_file(path);
  openvdb::io::File& f = *opened;
  const openvdb::GridBase::Ptr density_header =
      float_grid_header(f, density_grid, file, "density_grid");
  openvdb::GridBase::Ptr temperature_header;
  if (!temperature_grid.empty()) {
    temperature_header = float_grid_header(f, temperature_grid, file, "temperature_grid");
    if (!(temperature_header->constTransform() == density_header->constTransform()))
      throw InputError(file, temperature_grid,
                       fmt::format("grid transform differs from the density grid '{}''s; "
                                   "both must lie on the same voxels",
                                   density_grid));
  }
  VdbDensityVolume v;
  const GridPlacement index_placement =
      vdb_format::transform_to_placement(density_header->constTransform(), file, density_grid);

  const openvdb::FloatGrid::Ptr density = read_float_grid(f, density_grid, file);
  if (density->background() != 0.0f)
    throw InputError(file, density_grid,
                     fmt::format("background value {} (the density outside the active voxels) "
                                 "must be 0: a cloud ends where its active voxels do",
                                 density->background()));
  openvdb::CoordBBox box = density->evalActiveVoxelBoundingBox();
  if (box.empty()) {
    v.empty = true;
    box = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0));
  }
  const openvdb::Coord lo = box.min(), extent = box.dim();
  v.dims = {extent.x(), extent.y(), extent.z()};
  for (int a = 0; a < 3; ++a) v.index_min[a] = lo[a];
  const std::uint64_t grids = temperature_grid.empty() ? 1 : 2;
  const auto bytes = checked_product({static_cast<std::uint64_t>(extent.x()),
                                      static_cast<std::uint64_t>(extent.y()),
                                      static_cast<std::uint64_t>(extent.z()), grids * 4});
  check_memory(bytes.value_or(UINT64_MAX), file, density_grid,
               fmt::format("the active bounding box of {}x{}x{} voxels as {} dense float "
                           "grid{}",
                           extent.x(), extent.y(), extent.z(), grids, grids > 1 ? "s" : ""));

  // Voxel (0, 0, 0) of the dense arrays is OpenVDB's voxel `lo`.
  v.placement = index_placement;
  v.placement.origin_m =
      index_placement.origin_m +
      index_placement.rotation * (Vec3(lo.x(), lo.y(), lo.z()) * index_placement.voxel_size_m);
  v.density.assign(v.dims.count(), 0.0f);
  if (!v.empty) {
    DenseXYZ dense(box, v.density.data());
    openvdb::tools::copyToDense(*density, dense);
  }
  if (!temperature_grid.empty()) {
    const openvdb::FloatGrid::Ptr temperature = read_float_grid(f, temperature_grid, file);
    v.temperature.assign(v.dims.count(), 0.0f);
    DenseXYZ dense(box, v.temperature.data());
    openvdb::tools::copyToDense(*temperature, dense);
  }
  f.close();
  return v;
}

}  // namespace obscura
