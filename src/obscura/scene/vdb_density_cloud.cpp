#include "obscura/scene/vdb_density_cloud.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "obscura/io/json_reader.h"
#include "obscura/io/numbered_files.h"
#include "obscura/io/vdb_density_file.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/voxelise.h"
#include "obscura/optics/material.h"
#include "obscura/optics/material_species_optics.h"

namespace obscura {
namespace {

// `values` mapped in place to offset + scale × value, each of which must be
// finite and >= 0; errors name the voxel by its OpenVDB index.
void map_values(std::vector<float>& values, double scale, double offset, const VdbDensityVolume& v,
                const std::string& file, const std::string& grid, const char* what) {
  const GridDims& d = v.dims;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double mapped = offset + scale * static_cast<double>(values[i]);
    const auto stored = static_cast<float>(mapped);
    if (std::isfinite(stored) && stored >= 0.0f) {
      values[i] = stored;
      continue;
    }
    const std::size_t x = i % d.nx, y = (i / d.nx) % d.ny,
                      z = i / (static_cast<std::size_t>(d.nx) * d.ny);
    throw InputError(
        file,
        fmt::format("{} voxel ({},{},{})", grid, v.index_min[0] + static_cast<long long>(x),
                    v.index_min[1] + static_cast<long long>(y),
                    v.index_min[2] + static_cast<long long>(z)),
        fmt::format("value {} gives {} {}, which must be finite and >= 0", values[i], mapped,
                    what));
  }
}

// The material named by "material": a shipped name, or a material file
// (relative to the scene's folder).
Material cloud_material(JsonObject& o, const std::filesystem::path& base, Scene& scene) {
  const std::string name = o.string("material");
  const std::filesystem::path path(name);
  const bool is_path = name.find('/') != std::string::npos || path.extension() == ".json";
  Material m;
  try {
    m = is_path && path.is_relative() ? load_material(base / path) : load_material_by_name(name);
  } catch (const InputError& e) {
    if (e.file().empty()) throw o.error("material", e.detail());
    throw;
  }
  scene.input_files.push_back(m.file);
  return m;
}

std::vector<double> cloud_wavelengths(JsonObject& o) {
  const std::vector<double> w = o.numbers("wavelengths_um");
  if (w.empty()) throw o.error("wavelengths_um", "needs at least one wavelength (µm)");
  for (std::size_t k = 0; k < w.size(); ++k)
    if (!(w[k] > 0) || (k > 0 && !(w[k] > w[k - 1])))
      throw o.error("wavelengths_um",
                    fmt::format("{} µm: wavelengths must be > 0 and strictly increasing", w[k]));
  return w;
}

VdbDensityMapping parse_mapping(JsonObject& o) {
  VdbDensityMapping m;
  m.density_grid = o.string_or("density_grid", m.density_grid);
  if (m.density_grid.empty()) throw o.error("density_grid", "must name a grid");
  m.density_scale_g_m3 = o.positive("density_scale");
  if (o.has("temperature_grid")) {
    m.temperature_grid = o.string("temperature_grid");
    if (m.temperature_grid.empty()) throw o.error("temperature_grid", "must name a grid");
    if (o.has("ambient_temperature"))
      throw o.error("ambient_temperature",
                    "the temperature grid gives every voxel's temperature: give "
                    "\"temperature_offset\" for its zero instead");
    m.temperature_scale = o.number_or("temperature_scale", m.temperature_scale);
    m.temperature_offset_k = o.number_or("temperature_offset", m.temperature_offset_k);
  } else {
    for (const char* key : {"temperature_scale", "temperature_offset"})
      if (o.has(key))
        throw o.error(key, "maps the temperature grid's values: give \"temperature_grid\" too");
    m.ambient_temperature_k = o.positive_or("ambient_temperature", m.ambient_temperature_k);
  }
  m.position_m = o.vec3_or("position", m.position_m);
  return m;
}

std::optional<long long> frame_number(JsonObject& o, const std::string& key, std::size_t i) {
  const auto& f = o.array("frames");
  if (f.size() != 2 || !f[i].is_number_integer())
    throw o.error(key, "expected [first, last]: the frame numbers of the sequence, integers");
  return f[i].get<long long>();
}

// The AnimatedCloud of a numbered sequence: frame n at (n − first) / rate
// after the activation, played once; the last frame is held until the
// deactivation, and is gone one frame interval after it (a copy of the last
// frame closes the lifecycle's extinction phase: medium/lifecycle.h).
void add_sequence(JsonObject& o, const std::filesystem::path& pattern, const VdbDensityMapping& m,
                  const SpeciesOptics& optics, Scene& scene, int index) {
  std::optional<long long> first, last;
  if (o.has("frames")) {
    first = frame_number(o, "frames", 0);
    last = frame_number(o, "frames", 1);
    if (*last < *first) throw o.error("frames", "the last frame must not precede the first");
  }
  const double rate = o.positive("frame_rate_hz");
  const std::vector<NumberedFile> files =
      find_numbered_files(pattern, first, last, o.file(), o.path_of("file"));
  const AnimatedCloudKeys keys = read_animated_cloud_keys(o, index);
  o.finish();

  std::vector<ManifestKeyframe> keyframes;
  std::vector<double> times;
  for (const NumberedFile& f : files) {
    const double t = static_cast<double>(f.frame - files.front().frame) / rate;
    keyframes.push_back({f.file, t});
    times.push_back(t);
    scene.input_files.push_back(f.file);
  }
  keyframes.push_back({files.back().file, times.back() + 1.0 / rate});
  times.push_back(keyframes.back().time_s);
  LifecycleSpec spec;
  const int n = static_cast<int>(files.size());
  spec.init_end = spec.loop_start = spec.loop_end = n - 1;
  spec.extinction_start = n;
  CloudManifest manifest{pattern, std::move(keyframes),
                         Lifecycle(std::move(times), spec, pattern.string()), Trajectory()};
  auto cloud = std::make_shared<AnimatedCloud>(
      keys.name, std::move(manifest), keys.activation_s, keys.deactivation_s, keys.cache_keyframes,
      [m, optics](const std::filesystem::path& file) {
        return std::make_shared<const VoxelGrid>(read_vdb_density_cloud(file, m, optics));
      });
  // The first frame now, through the cache: a wrong grid name or mapping
  // fails at load, not part-way through a render.
  cloud->stage_grid(keys.activation_s);
  scene.animated_clouds.push_back(std::move(cloud));
}

}  // namespace

namespace {

// One volume of the file's grids as a voxel grid (read_vdb_density_cloud).
VoxelGrid voxels_of(VdbDensityVolume v, const std::filesystem::path& file,
                    const VdbDensityMapping& m, const SpeciesOptics& optics) {
  const std::string source = file.string();
  ConcentrationFrame frame;
  ScalarGrid& c = frame.concentration_g_m3;
  c.dims = v.dims;
  c.placement = v.placement;
  c.placement.origin_m = c.placement.origin_m + m.position_m;
  map_values(v.density, m.density_scale_g_m3, 0.0, v, source, m.density_grid,
             "g/m3 of concentration (× density_scale)");
  c.values = std::move(v.density);
  if (!v.temperature.empty()) {
    map_values(v.temperature, m.temperature_scale, m.temperature_offset_k, v, source,
               m.temperature_grid, "K (temperature_offset + temperature_scale × value)");
    frame.temperature_k = ScalarGrid{c.dims, c.placement, std::move(v.temperature)};
  }
  return voxelise(frame, optics, m.ambient_temperature_k, source);
}

}  // namespace

VoxelGrid read_vdb_density_cloud(const std::filesystem::path& file, const VdbDensityMapping& m,
                                 const SpeciesOptics& optics) {
  return voxels_of(read_vdb_density(file, m.density_grid, m.temperature_grid), file, m, optics);
}

std::vector<VoxelGrid> read_vdb_density_cloud_parts(const std::filesystem::path& file,
                                                    const VdbDensityMapping& m,
                                                    const SpeciesOptics& optics) {
  std::vector<VoxelGrid> grids;
  for (VdbDensityVolume& v : read_vdb_density_parts(file, m.density_grid, m.temperature_grid))
    grids.push_back(voxels_of(std::move(v), file, m, optics));
  return grids;
}

void parse_vdb_density_cloud(JsonObject& o, const std::filesystem::path& base, Scene& scene,
                             int index) {
  std::filesystem::path file = o.string("file");
  if (file.empty()) throw o.error("file", "empty file name");
  if (file.is_relative()) file = base / file;
  const Material material = cloud_material(o, base, scene);
  const std::vector<double> wavelengths = cloud_wavelengths(o);
  const double humidity = o.number_or("relative_humidity", 0.0);
  if (!(humidity >= 0 && humidity < 1))
    throw o.error("relative_humidity", "must lie in [0, 1) (a fraction, not per cent)");
  const VdbDensityMapping mapping = parse_mapping(o);
  SpeciesOptics optics;
  try {
    optics = material_species_optics(material, wavelengths, humidity, 0, scene.warnings);
  } catch (const InputError& e) {
    throw o.error("wavelengths_um", e.what());
  }
  if (is_numbered_pattern(file)) return add_sequence(o, file, mapping, optics, scene, index);
  for (const char* key :
       {"frame_rate_hz", "frames", "activation", "deactivation", "name", "cache_keyframes"})
    if (o.has(key))
      throw o.error(key,
                    "belongs to a numbered sequence (a file name with a run of '#', such as "
                    "smoke_####.vdb); one file is a cloud present at all times");
  o.finish();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw o.error("file", fmt::format("cannot open VDB file '{}': no such file", file.string()));
  scene.input_files.push_back(file);
  // A sparse file's clusters far apart are separate grids (io/vdb_density_file.h).
  for (VoxelGrid& grid : read_vdb_density_cloud_parts(file, mapping, optics))
    scene.static_clouds.push_back(
        std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(std::move(grid))));
}

}  // namespace obscura
