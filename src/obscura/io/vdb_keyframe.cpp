#include "obscura/io/vdb_keyframe.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <optional>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/vdb_keyframe_forms.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_keyframe_metadata.h"
#include "obscura/io/vdb_open.h"

namespace obscura {
namespace {

using vdb_format::CommonHeader;
using vdb_format::GridSpec;
using vdb_format::kConcentrationUnits;
using vdb_format::kFormSpecies;
using vdb_format::MetaReader;
using vdb_format::read_common_header;
using vdb_format::read_species_grids;
using vdb_format::read_spectral_grids;
using vdb_format::spectral_layout;

struct ReadResult {
  CloudKeyframe keyframe;
  openvdb::MetaMap::Ptr file_metadata;
  std::string form;
  std::optional<SpeciesCloud> species;  // species form, when asked to keep it
};

ReadResult read_keyframe(const std::filesystem::path& path, bool keep_species) {
  const std::string file = path.string();
  const std::unique_ptr<openvdb::io::File> opened = vdb_format::open_checked_vdb_file(path);
  openvdb::io::File& f = *opened;

  ReadResult result;
  result.file_metadata = f.getMetadata();
  const MetaReader meta(*result.file_metadata, file);
  CommonHeader h = read_common_header(meta, *result.file_metadata, file);
  result.form = h.form;
  result.keyframe.time_s = h.time_s;
  if (h.form == kFormSpecies) {
    SpeciesCloud cloud = read_species_grids(f, meta, *result.file_metadata, h, file);
    f.close();
    result.keyframe.grid = std::make_shared<VoxelGrid>(expand_species(cloud, file));
    if (keep_species) result.species = std::move(cloud);
  } else {
    result.keyframe.grid = read_spectral_grids(f, meta, *result.file_metadata, h, file);
    f.close();
  }
  return result;
}

ChannelSummary summarise(const std::string& name, const std::string& units, const float* v,
                         std::size_t count) {
  ChannelSummary s;
  s.name = name;
  s.units = units;
  const auto [lo, hi] = std::minmax_element(v, v + count);
  s.min = *lo;
  s.max = *hi;
  s.nonzero_voxels = static_cast<std::size_t>(count - std::count(v, v + count, 0.0f));
  return s;
}

}  // namespace

CloudKeyframe read_cloud_keyframe(const std::filesystem::path& path) {
  return read_keyframe(path, /*keep_species=*/false).keyframe;
}

KeyframeInfo inspect_cloud_keyframe(const std::filesystem::path& path) {
  ReadResult r = read_keyframe(path, /*keep_species=*/true);
  const VoxelGrid& grid = *r.keyframe.grid;
  KeyframeInfo info;
  info.file = path;
  std::error_code ec;
  info.file_bytes = std::filesystem::file_size(path, ec);
  info.form = r.form;
  info.dims = grid.dims();
  info.wavelengths_um = grid.wavelengths_um();
  info.placement = grid.placement();
  info.world_bounds_m = grid.world_bounds();
  info.time_s = r.keyframe.time_s;
  info.memory_bytes = grid.memory_bytes();
  const std::size_t count = grid.dims().count();
  const std::vector<GridSpec> layout = spectral_layout(grid.wavelengths_um());
  for (int c = 0; c < grid.channel_count(); ++c)
    info.channels.push_back(summarise(layout[c].name, layout[c].units, grid.channel(c), count));
  if (r.species) {
    const SpeciesCloud& cloud = *r.species;
    info.compact_bytes = cloud.memory_bytes();
    for (std::size_t s = 0; s < cloud.species.size(); ++s)
      info.species.push_back(
          {cloud.species[s],
           summarise(species_concentration_name(static_cast<int>(s)), kConcentrationUnits,
                     cloud.concentration_g_m3[s].data(), count)});
  }
  for (auto it = r.file_metadata->beginMeta(); it != r.file_metadata->endMeta(); ++it)
    info.metadata[it->first] = it->second ? it->second->str() : std::string();
  return info;
}

}  // namespace obscura
