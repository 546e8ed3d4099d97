// The spectral form of a cloud keyframe (io/vdb_keyframe.h): σa, σs, g per
// wavelength and temperature, one float grid each.
#include <fmt/format.h>

#include <stdexcept>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vdb_keyframe_forms.h"
#include "obscura/io/vdb_keyframe_grids.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_keyframe_metadata.h"
#include "obscura/io/vdb_keyframe_placement.h"

namespace obscura::vdb_format {

std::shared_ptr<VoxelGrid> read_spectral_grids(openvdb::io::File& f, const MetaReader& meta,
                                               const openvdb::MetaMap& file_metadata,
                                               CommonHeader& h, const std::string& file) {
  require_units(meta, "coefficient_units", kCoefficientUnits, file);
  const int n = static_cast<int>(h.wavelengths_um.size());
  // Before reading any voxel data: refuse dims that overflow or exceed memory.
  VoxelGrid::checked_storage_bytes(h.dims, n, file);
  check_no_extra_indexed_grids(f, {"sigma_a_", "sigma_s_", "g_"}, n, file, [&](int idx) {
    return fmt::format("grid index {} is beyond spectral_count {}", idx, n);
  });
  const std::vector<GridSpec> layout = spectral_layout(h.wavelengths_um);
  const GridPlacement placement = read_layout_placement(f, file_metadata, layout, h.dims, file);
  auto grid = std::make_shared<VoxelGrid>(h.dims, placement, std::move(h.wavelengths_um), file);
  for (int c = 0; c < grid->channel_count(); ++c) {
    if (layout[c].name != grid->channel_name(c))  // the layout must mirror channel_name
      throw std::logic_error("vdb_keyframe: channel name mismatch for " + layout[c].name);
    read_dense_grid(f, layout[c].name, h.dims, grid->channel(c), file);
  }
  grid->validate(file);
  return grid;
}

}  // namespace obscura::vdb_format

namespace obscura {

using vdb_format::check_time_and_metadata;
using vdb_format::common_metadata;
using vdb_format::ensure_openvdb_initialized;
using vdb_format::GridSpec;
using vdb_format::kCoefficientUnits;
using vdb_format::kFormSpectral;
using vdb_format::make_float_grid;
using vdb_format::placement_to_transform;
using vdb_format::spectral_layout;
using vdb_format::write_keyframe_file;

void write_cloud_keyframe(const std::filesystem::path& path, const VoxelGrid& grid, double time_s,
                          const std::map<std::string, std::string>& extra_metadata) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  check_time_and_metadata(file, time_s, extra_metadata);
  grid.validate(file);  // an invalid grid would only be refused by the reader

  openvdb::MetaMap meta = common_metadata(kFormSpectral, time_s, grid.wavelengths_um(), grid.dims(),
                                          grid.placement(), extra_metadata);
  meta.insertMeta("coefficient_units", openvdb::StringMetadata(kCoefficientUnits));
  const openvdb::math::Transform::Ptr xf = placement_to_transform(grid.placement());
  const std::vector<GridSpec> layout = spectral_layout(grid.wavelengths_um());
  openvdb::GridPtrVec grids;
  for (int c = 0; c < grid.channel_count(); ++c)
    grids.push_back(make_float_grid(layout[c], grid.channel(c), grid.dims(), *xf));
  write_keyframe_file(path, grids, meta);
}

}  // namespace obscura
