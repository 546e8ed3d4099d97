// The species form of a cloud keyframe (io/vdb_keyframe.h): a concentration
// grid per particle species and the temperature, with the species' optics as
// JSON file metadata; the reader expands it to the spectral VoxelGrid.
#include <fmt/format.h>

#include <cstdint>
#include <nlohmann/json.hpp>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/io/json_document.h"
#include "obscura/io/json_reader.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vdb_keyframe_forms.h"
#include "obscura/io/vdb_keyframe_grids.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_keyframe_metadata.h"
#include "obscura/io/vdb_keyframe_placement.h"

namespace obscura::vdb_format {
namespace {

// The "species_optics" metadata: a JSON array of {name, wavelengths_um,
// mass_absorption_m2_g, mass_scattering_m2_g, asymmetry}, one per species,
// each at exactly the file's wavelengths.
std::vector<SpeciesOptics> parse_species_optics(const std::string& text, std::size_t count,
                                                const std::vector<double>& wavelengths_um,
                                                const std::string& file) {
  nlohmann::json doc;
  try {
    doc = parse_json_document(text, file);
  } catch (const InputError& e) {
    throw InputError(file, "species_optics", fmt::format("is not valid JSON ({})", e.detail()));
  }
  if (!doc.is_array())
    throw InputError(file, "species_optics", "must be a JSON array with one object per species");
  if (doc.size() != count)
    throw InputError(file, "species_optics",
                     fmt::format("lists {} species but species_count is {}", doc.size(), count));
  std::vector<SpeciesOptics> species;
  for (std::size_t s = 0; s < count; ++s) {
    const std::string field = fmt::format("species_optics/{}", s);
    JsonObject o(doc[s], file, field);
    SpeciesOptics optics;
    optics.name = o.string("name");
    optics.wavelengths_um = o.numbers("wavelengths_um");
    optics.mass_absorption_m2_g = o.numbers("mass_absorption_m2_g");
    optics.mass_scattering_m2_g = o.numbers("mass_scattering_m2_g");
    optics.asymmetry = o.numbers("asymmetry");
    o.finish();
    check_species_optics(optics, wavelengths_um, file, field);
    species.push_back(std::move(optics));
  }
  return species;
}

std::string format_species_optics(const std::vector<SpeciesOptics>& species) {
  nlohmann::json doc = nlohmann::json::array();
  // nlohmann writes the shortest decimal that reads back to the same double.
  for (const SpeciesOptics& o : species)
    doc.push_back({{"name", o.name},
                   {"wavelengths_um", o.wavelengths_um},
                   {"mass_absorption_m2_g", o.mass_absorption_m2_g},
                   {"mass_scattering_m2_g", o.mass_scattering_m2_g},
                   {"asymmetry", o.asymmetry}});
  return doc.dump();
}

// Before reading any voxel data: the expanded grid and, while it is being
// expanded, the compact arrays of `ns` species must fit in memory.
void check_species_memory(const CommonHeader& h, std::size_t ns, const std::string& file) {
  const std::uint64_t expanded =
      VoxelGrid::checked_storage_bytes(h.dims, static_cast<int>(h.wavelengths_um.size()), file);
  std::uint64_t compact = 0;
  if (__builtin_mul_overflow(static_cast<std::uint64_t>(h.dims.count()),
                             static_cast<std::uint64_t>((ns + 1) * sizeof(float)), &compact) ||
      expanded + compact < expanded || expanded + compact > memory_limit_bytes())
    throw InputError(
        file, "dims",
        fmt::format("grid {}x{}x{} with {} species and {} wavelengths needs {:.3g} "
                    "GiB but only {}",
                    h.dims.nx, h.dims.ny, h.dims.nz, ns, h.wavelengths_um.size(),
                    (static_cast<double>(expanded) + static_cast<double>(compact)) / 1073741824.0,
                    memory_limit_text()));
}

}  // namespace

SpeciesCloud read_species_grids(openvdb::io::File& f, const MetaReader& meta,
                                const openvdb::MetaMap& file_metadata, CommonHeader& h,
                                const std::string& file) {
  require_units(meta, "concentration_units", kConcentrationUnits, file);
  const long long species_count = meta.get_int("species_count");
  if (species_count <= 0 || species_count > 999)  // grid names carry 3 digits
    throw InputError(file, "species_count",
                     fmt::format("{} must be between 1 and 999", species_count));
  const std::size_t ns = static_cast<std::size_t>(species_count);
  SpeciesCloud cloud;
  cloud.species =
      parse_species_optics(meta.get_string("species_optics"), ns, h.wavelengths_um, file);

  check_species_memory(h, ns, file);
  check_no_extra_indexed_grids(f, {"concentration_"}, static_cast<int>(ns), file, [&](int idx) {
    return fmt::format("grid index {} is beyond species_count {}", idx, ns);
  });
  check_no_extra_indexed_grids(f, {"sigma_a_", "sigma_s_", "g_"}, 0, file, [](int) {
    return std::string("spectral grid in a species-form keyframe (obscura_form 'species')");
  });
  const std::vector<GridSpec> layout = species_layout(cloud.species);
  cloud.placement = read_layout_placement(f, file_metadata, layout, h.dims, file);
  cloud.dims = h.dims;
  cloud.wavelengths_um = std::move(h.wavelengths_um);
  const std::size_t count = h.dims.count();
  cloud.concentration_g_m3.resize(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    cloud.concentration_g_m3[s].resize(count);
    read_dense_grid(f, layout[s].name, cloud.dims, cloud.concentration_g_m3[s].data(), file);
  }
  cloud.temperature_k.resize(count);
  read_dense_grid(f, kTransformGrid, cloud.dims, cloud.temperature_k.data(), file);
  validate_species_cloud(cloud, file);
  return cloud;
}

}  // namespace obscura::vdb_format

namespace obscura {

using vdb_format::check_time_and_metadata;
using vdb_format::common_metadata;
using vdb_format::ensure_openvdb_initialized;
using vdb_format::format_species_optics;
using vdb_format::GridSpec;
using vdb_format::kConcentrationUnits;
using vdb_format::kFormSpecies;
using vdb_format::make_float_grid;
using vdb_format::placement_to_transform;
using vdb_format::species_layout;
using vdb_format::write_keyframe_file;

void write_species_keyframe(const std::filesystem::path& path, const SpeciesCloud& cloud,
                            double time_s,
                            const std::map<std::string, std::string>& extra_metadata) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  check_time_and_metadata(file, time_s, extra_metadata);
  validate_species_cloud(cloud, file);  // an invalid cloud would only be refused by the reader

  openvdb::MetaMap meta = common_metadata(kFormSpecies, time_s, cloud.wavelengths_um, cloud.dims,
                                          cloud.placement, extra_metadata);
  meta.insertMeta("concentration_units", openvdb::StringMetadata(kConcentrationUnits));
  meta.insertMeta("species_count", openvdb::Int32Metadata(static_cast<int>(cloud.species.size())));
  meta.insertMeta("species_optics", openvdb::StringMetadata(format_species_optics(cloud.species)));
  const openvdb::math::Transform::Ptr xf = placement_to_transform(cloud.placement);
  const std::vector<GridSpec> layout = species_layout(cloud.species);
  openvdb::GridPtrVec grids;
  for (std::size_t s = 0; s < cloud.species.size(); ++s)
    grids.push_back(
        make_float_grid(layout[s], cloud.concentration_g_m3[s].data(), cloud.dims, *xf));
  grids.push_back(make_float_grid(layout.back(), cloud.temperature_k.data(), cloud.dims, *xf));
  write_keyframe_file(path, grids, meta);
}

}  // namespace obscura
