#include "obscura/prep/prepare_config.h"

#include <fmt/format.h>

#include <limits>

#include "obscura/core/error.h"
#include "obscura/core/time_steps.h"
#include "obscura/io/json_reader.h"

namespace obscura {
namespace {

// "times_s": [t0, t1, ...] or {"start": a, "end": b, "step": h} (both ends included).
std::vector<double> parse_times(JsonObject& root) {
  const std::string key = "times_s";
  const auto& raw = root.raw(key);
  std::vector<double> times;
  if (raw.is_array()) {
    times = root.numbers(key);
  } else {
    JsonObject t = root.object(key);
    const double start = t.number("start"), end = t.number("end"), step = t.positive("step");
    if (!(end >= start)) throw t.error("end", "must be >= start");
    if (time_step_count(start, end, step) > 100000)
      throw t.error("step", "gives more than 100000 keyframes");
    times = time_steps(start, end, step);
    t.finish();
  }
  if (times.size() < 2)
    throw root.error(key, "needs at least two times (a lifecycle needs two keyframes)");
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!(times[i] >= 0) || (i > 0 && !(times[i] > times[i - 1])))
      throw InputError(root.file(), fmt::format("{}/{}", root.path_of(key), i),
                       "times must be >= 0 s and strictly increasing");
  return times;
}

// The material, the humidity and the wavelengths.
void read_material_settings(JsonObject& root, PrepareConfig& c) {
  const std::string material_name = root.string("material");
  try {
    c.material = load_material_by_name(material_name);
  } catch (const InputError& e) {
    throw InputError(c.file, "/material", e.what());
  }
  c.relative_humidity = root.number_or("relative_humidity", 0.0);
  if (!(c.relative_humidity >= 0 && c.relative_humidity < 1))
    throw root.error("relative_humidity", "must lie in [0, 1)");
  c.wavelengths_um = root.numbers("wavelengths_um");
  if (c.wavelengths_um.empty()) throw root.error("wavelengths_um", "needs at least one wavelength");
  for (std::size_t i = 0; i < c.wavelengths_um.size(); ++i)
    if (!(c.wavelengths_um[i] > 0) || (i > 0 && !(c.wavelengths_um[i] > c.wavelengths_um[i - 1])))
      throw InputError(c.file, fmt::format("/wavelengths_um/{}", i),
                       "must be > 0 µm and strictly increasing");
}

// A file the configuration names: a relative path is relative to the
// configuration's folder.
std::filesystem::path config_relative(const std::filesystem::path& config_path,
                                      const std::string& name) {
  std::filesystem::path p = name;
  if (p.is_relative()) p = config_path.parent_path() / p;
  return p;
}

DispersionSource dispersion_source(JsonObject& root) {
  DispersionSource s;
  s.config = parse_dispersion_config(root.object("dispersion"));
  s.config.source = root.file();
  s.times_s = parse_times(root);
  s.voxel_size_m = root.positive("voxel_size_m");
  return s;
}

VtkSource vtk_source(JsonObject& root, const std::filesystem::path& config_path) {
  VtkSource s;
  JsonObject vtk = root.object("vtk");
  s.names.concentration = vtk.string_or("concentration", s.names.concentration);
  s.names.temperature = vtk.string_or("temperature", "");
  s.names.concentration_to_g_m3 = vtk.positive_or("concentration_to_g_m3", 1.0);
  const auto& frames = vtk.array("frames");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    JsonObject f(frames[i], root.file(), fmt::format("{}/{}", vtk.path_of("frames"), i));
    const double t = f.number("time_s");
    s.time_and_path.emplace_back(t, config_relative(config_path, f.string("file")).string());
    f.finish();
  }
  s.ambient_temperature_k = vtk.positive_or("ambient_temperature_k", s.ambient_temperature_k);
  vtk.finish();
  return s;
}

NetcdfSource netcdf_source(JsonObject& root, const std::filesystem::path& config_path) {
  NetcdfSource s;
  JsonObject nc = root.object("netcdf");
  s.file = config_relative(config_path, nc.string("file"));
  s.options.concentration = nc.string_or("concentration", s.options.concentration);
  s.options.temperature = nc.string_or("temperature", "");
  s.options.concentration_units_if_missing = nc.string_or("concentration_units_if_missing", "");
  s.options.missing_concentration_as_zero = nc.boolean_or("missing_concentration_as_zero", false);
  s.ambient_temperature_k = nc.positive_or("ambient_temperature_k", s.ambient_temperature_k);
  nc.finish();
  return s;
}

std::optional<LifecycleSpec> lifecycle_spec(JsonObject& root) {
  auto lc = root.optional_object("lifecycle");
  if (!lc) return std::nullopt;
  // Keyframe indexes: read as 64-bit and checked before narrowing, so that a
  // huge value is named, not wrapped into a small one (Lifecycle checks the
  // rest against the frames).
  const auto index = [&](const char* key) {
    const long long v = lc->integer(key);
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      throw lc->error(key, "is not a keyframe index");
    return static_cast<int>(v);
  };
  LifecycleSpec spec;
  spec.init_end = index("init_end");
  spec.loop_start = index("loop_start");
  spec.loop_end = index("loop_end");
  spec.loop_wrap_s = lc->number("loop_wrap");
  spec.extinction_start = index("extinction_start");
  lc->finish();
  return spec;
}

}  // namespace

PrepareConfig read_prepare_config(const nlohmann::json& doc,
                                  const std::filesystem::path& config_path) {
  PrepareConfig c;
  c.file = config_path.string();
  JsonObject root(doc, c.file, "");
  root.string_or("description", "");
  read_material_settings(root, c);

  // Which keyframe form to write (docs/formats.md): both read to the same grids.
  c.output_form = root.string_or("output_form", "spectral");
  if (c.output_form != "spectral" && c.output_form != "species")
    throw root.error("output_form", fmt::format("unknown form '{}' (expected spectral or species)",
                                                c.output_form));

  const std::string source = root.string("source");
  if (source == "dispersion")
    c.source = dispersion_source(root);
  else if (source == "vtk")
    c.source = vtk_source(root, config_path);
  else if (source == "netcdf")
    c.source = netcdf_source(root, config_path);
  else
    throw root.error(
        "source", fmt::format("unknown source '{}' (expected dispersion, vtk or netcdf)", source));
  c.lifecycle = lifecycle_spec(root);
  root.finish();
  return c;
}

}  // namespace obscura
