#include "obscura/prep/prepare.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/time_steps.h"
#include "obscura/io/cloud_manifest.h"
#include "obscura/io/json_reader.h"
#include "obscura/io/netcdf_cf.h"
#include "obscura/io/stale_temporaries.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/optics/material.h"
#include "obscura/prep/dispersion/dispersion_config.h"
#include "obscura/prep/dispersion/dispersion_grid.h"
#include "obscura/prep/suggested_lifecycle.h"
#include "obscura/prep/voxelise.h"

namespace obscura {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

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

// The material's mass coefficients at the cloud's wavelengths. Where the
// sources give only extinction (tabulated IR bands), the extinction is taken
// as absorption with g = 0, and a warning says so.
SpeciesOptics species_optics(const Material& material, const std::vector<double>& wavelengths_um,
                             double humidity, int threads, std::vector<std::string>& warnings) {
  SpeciesOptics s;
  s.name = material.name;
  s.wavelengths_um = wavelengths_um;
  const std::vector<MaterialOptics> o = optics_at(material, wavelengths_um, humidity, threads);
  for (const MaterialOptics& m : o) {
    if (std::isnan(m.mass_scattering_m2_g) || std::isnan(m.asymmetry)) {
      warnings.push_back(
          fmt::format("{} at {} um: the sources give extinction only ({} m2/g); it is "
                      "taken as absorption (albedo 0, g 0)",
                      material.name, m.wavelength_um, m.mass_extinction_m2_g));
      s.mass_absorption_m2_g.push_back(m.mass_extinction_m2_g);
      s.mass_scattering_m2_g.push_back(0.0);
      s.asymmetry.push_back(0.0);
    } else {
      s.mass_absorption_m2_g.push_back(m.mass_absorption_m2_g);
      s.mass_scattering_m2_g.push_back(m.mass_scattering_m2_g);
      s.asymmetry.push_back(std::clamp(m.asymmetry, -0.999, 0.999));
    }
  }
  return s;
}

void write_manifest(const std::filesystem::path& path, const PrepareReport& r) {
  nlohmann::json doc;
  for (std::size_t i = 0; i < r.keyframes.size(); ++i)
    doc["keyframes"].push_back(
        {{"file", r.keyframes[i].filename().string()}, {"time", r.times_s[i]}});
  doc["lifecycle"] = {{"init_end", r.lifecycle.init_end},
                      {"loop_start", r.lifecycle.loop_start},
                      {"loop_end", r.lifecycle.loop_end},
                      {"loop_wrap", r.lifecycle.loop_wrap_s},
                      {"extinction_start", r.lifecycle.extinction_start}};
  // The clouds are computed in world coordinates (the wind moves them): the
  // trajectory is the identity.
  doc["trajectory"] = {{"keys", {{{"time", 0.0}, {"position", {0, 0, 0}}, {"heading_deg", 0}}}},
                       {"interpolation", "linear"}};
  std::ofstream out(path);
  out << doc.dump(2) << "\n";
  if (!out) throw Error("cannot write " + path.string());
}

// Progress, and where a SIGINT or SIGTERM stops a preparation (the
// temporary folder is then removed).
void say(const PrepareOptions& options, const std::string& line) {
  throw_if_interrupted();
  if (options.progress) options.progress(line);
}

// What the cloud is made of: the material, the humidity and the wavelengths
// (into the report).
struct MaterialSettings {
  Material material;
  double humidity = 0;
};

MaterialSettings read_material_settings(JsonObject& root, PrepareReport& report) {
  const std::string& file = root.file();
  MaterialSettings m;
  const std::string material_name = root.string("material");
  try {
    m.material = load_material_by_name(material_name);
  } catch (const InputError& e) {
    throw InputError(file, "/material", e.what());
  }
  report.material = m.material.name;
  m.humidity = root.number_or("relative_humidity", 0.0);
  if (!(m.humidity >= 0 && m.humidity < 1))
    throw root.error("relative_humidity", "must lie in [0, 1)");
  report.wavelengths_um = root.numbers("wavelengths_um");
  if (report.wavelengths_um.empty())
    throw root.error("wavelengths_um", "needs at least one wavelength");
  for (std::size_t i = 0; i < report.wavelengths_um.size(); ++i)
    if (!(report.wavelengths_um[i] > 0) ||
        (i > 0 && !(report.wavelengths_um[i] > report.wavelengths_um[i - 1])))
      throw InputError(file, fmt::format("/wavelengths_um/{}", i),
                       "must be > 0 µm and strictly increasing");
  return m;
}

// Concentrations over time, from one of the sources, and what the keyframes
// need to know of their origin.
struct Concentrations {
  ConcentrationSeries series;
  std::optional<double> burn_end_s;  // dispersion: when the last device stops
  double ambient_k = 288.15;
};

Concentrations dispersion_concentrations(JsonObject& root, const PrepareOptions& options,
                                         PrepareReport& report) {
  Concentrations c;
  DispersionConfig config = parse_dispersion_config(root.object("dispersion"));
  config.source = root.file();
  const std::vector<double> times = parse_times(root);
  const double voxel = root.positive("voxel_size_m");
  c.ambient_k = config.ambient_temperature_k;
  double end = 0;
  for (const SmokeDevice& d : config.devices) {
    end = std::max(end, d.start_s + d.burn_time_s);
    report.released_mass_g += d.released_mass_g();
  }
  c.burn_end_s = end;
  say(options,
      fmt::format("dispersion: {} devices, {} frames from {} to {} s at {} m voxels",
                  config.devices.size(), times.size(), times.front(), times.back(), voxel));
  c.series = dispersion_series(config, times, voxel, options.threads);
  return c;
}

// A file the configuration names: a relative path is relative to the
// configuration's folder.
std::filesystem::path config_relative(const std::filesystem::path& config_path,
                                      const std::string& name) {
  std::filesystem::path p = name;
  if (p.is_relative()) p = config_path.parent_path() / p;
  return p;
}

Concentrations vtk_concentrations(JsonObject& root, const std::filesystem::path& config_path,
                                  const PrepareOptions& options) {
  Concentrations c;
  JsonObject vtk = root.object("vtk");
  VtkArrayNames names;
  names.concentration = vtk.string_or("concentration", names.concentration);
  names.temperature = vtk.string_or("temperature", "");
  names.concentration_to_g_m3 = vtk.positive_or("concentration_to_g_m3", 1.0);
  const auto& frames = vtk.array("frames");
  std::vector<std::pair<double, std::string>> time_and_path;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    JsonObject f(frames[i], root.file(), fmt::format("{}/{}", vtk.path_of("frames"), i));
    const double t = f.number("time_s");
    time_and_path.emplace_back(t, config_relative(config_path, f.string("file")).string());
    f.finish();
  }
  c.ambient_k = vtk.positive_or("ambient_temperature_k", c.ambient_k);
  vtk.finish();
  say(options, fmt::format("VTK: {} frames", time_and_path.size()));
  c.series = read_vtk_series(time_and_path, names);
  return c;
}

Concentrations netcdf_concentrations(JsonObject& root, const std::filesystem::path& config_path,
                                     const PrepareOptions& options) {
  Concentrations c;
  JsonObject nc = root.object("netcdf");
  NetcdfReadOptions o;
  const std::filesystem::path p = config_relative(config_path, nc.string("file"));
  o.concentration = nc.string_or("concentration", o.concentration);
  o.temperature = nc.string_or("temperature", "");
  o.concentration_units_if_missing = nc.string_or("concentration_units_if_missing", "");
  o.missing_concentration_as_zero = nc.boolean_or("missing_concentration_as_zero", false);
  c.ambient_k = nc.positive_or("ambient_temperature_k", c.ambient_k);
  nc.finish();
  say(options, "NetCDF: " + p.string());
  c.series = read_netcdf_cf(p, o);
  return c;
}

// The "source" the configuration names; at least two frames. Fills in the
// report's times and grid.
Concentrations read_concentrations(JsonObject& root, const std::filesystem::path& config_path,
                                   const PrepareOptions& options, PrepareReport& report) {
  const std::string source = root.string("source");
  Concentrations c;
  if (source == "dispersion") {
    c = dispersion_concentrations(root, options, report);
  } else if (source == "vtk") {
    c = vtk_concentrations(root, config_path, options);
  } else if (source == "netcdf") {
    c = netcdf_concentrations(root, config_path, options);
  } else {
    throw root.error(
        "source", fmt::format("unknown source '{}' (expected dispersion, vtk or netcdf)", source));
  }
  if (c.series.frames.size() < 2)
    throw InputError(root.file(), "/source",
                     "needs at least two frames (a lifecycle needs two keyframes)");
  for (const auto& f : c.series.frames) report.times_s.push_back(f.time_s);
  report.dims = c.series.frames[0].concentration_g_m3.dims;
  report.voxel_size_m = c.series.frames[0].concentration_g_m3.placement.voxel_size_m;
  return c;
}

// The lifecycle: given, or suggested from the timing; validated.
void read_lifecycle(JsonObject& root, std::optional<double> burn_end_s, PrepareReport& report) {
  if (auto lc = root.optional_object("lifecycle")) {
    report.lifecycle.init_end = static_cast<int>(lc->integer("init_end"));
    report.lifecycle.loop_start = static_cast<int>(lc->integer("loop_start"));
    report.lifecycle.loop_end = static_cast<int>(lc->integer("loop_end"));
    report.lifecycle.loop_wrap_s = lc->number("loop_wrap");
    report.lifecycle.extinction_start = static_cast<int>(lc->integer("extinction_start"));
    lc->finish();
    report.lifecycle_suggested = false;
  } else {
    report.lifecycle = suggest_lifecycle(report.times_s, burn_end_s);
  }
  Lifecycle(report.times_s, report.lifecycle, root.file() + ": /lifecycle");  // validates
}

// The keyframes and the manifest, written into a temporary sibling folder
// that is renamed to `out_dir` when complete (and removed on failure).
void write_cloud(const std::filesystem::path& out_dir, const Concentrations& c,
                 const SpeciesOptics& optics, const std::string& output_form,
                 const std::string& file, const PrepareOptions& options, PrepareReport& report) {
  namespace fs = std::filesystem;
  const ConcentrationSeries& series = c.series;
  const fs::path parent = out_dir.parent_path().empty() ? fs::path(".") : out_dir.parent_path();
  fs::create_directories(parent);
  remove_stale_temporaries(parent);  // a killed prepare's ".<name>.partial-<pid>"
  const fs::path temp =
      parent / fmt::format(".{}.partial-{}", out_dir.filename().string(), ::getpid());
  fs::remove_all(temp);
  fs::create_directories(temp);
  try {
    const auto t2 = Clock::now();
    const std::map<std::string, std::string> meta{{"material", report.material},
                                                  {"source", series.source},
                                                  {"command_line", options.command_line}};
    for (std::size_t i = 0; i < series.frames.size(); ++i) {
      const ConcentrationFrame& frame = series.frames[i];
      const std::string name = fmt::format("keyframe_{:04d}.vdb", i);
      if (output_form == "species")
        write_species_keyframe(temp / name, species_cloud(frame, optics, c.ambient_k, file),
                               frame.time_s, meta);
      else
        write_cloud_keyframe(temp / name, voxelise(frame, optics, c.ambient_k, file), frame.time_s,
                             meta);
      report.keyframes.push_back(out_dir / name);
      say(options,
          fmt::format("keyframe {} of {} at {} s", i + 1, series.frames.size(), frame.time_s));
    }
    write_manifest(temp / "cloud.json", report);
    read_cloud_manifest(temp / "cloud.json");  // what we wrote must read back
    report.seconds_keyframes = since(t2);
    for (const auto& e : fs::directory_iterator(temp))
      report.bytes_written += fs::file_size(e.path());
    if (fs::exists(out_dir)) fs::remove(out_dir);  // an empty folder, checked before
    fs::rename(temp, out_dir);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(temp, ec);
    throw;
  }
}

}  // namespace

PrepareReport prepare_cloud(const std::filesystem::path& config_path,
                            const std::filesystem::path& out_dir, const PrepareOptions& options) {
  return prepare_cloud(read_json_file(config_path.string()), config_path, out_dir, options);
}

PrepareReport prepare_cloud(const nlohmann::json& doc, const std::filesystem::path& config_path,
                            const std::filesystem::path& out_dir, const PrepareOptions& options) {
  namespace fs = std::filesystem;
  const std::string file = config_path.string();
  JsonObject root(doc, file, "");
  PrepareReport report;

  if (fs::exists(out_dir) && !(fs::is_directory(out_dir) && fs::is_empty(out_dir)))
    throw InputError(out_dir.string(), "",
                     "exists and is not an empty folder; remove it or choose another");

  root.string_or("description", "");
  const MaterialSettings material = read_material_settings(root, report);

  // Which keyframe form to write (docs/formats.md): both read to the same grids.
  const std::string output_form = root.string_or("output_form", "spectral");
  if (output_form != "spectral" && output_form != "species")
    throw root.error("output_form",
                     fmt::format("unknown form '{}' (expected spectral or species)", output_form));
  report.output_form = output_form;

  const auto t0 = Clock::now();
  const Concentrations concentrations = read_concentrations(root, config_path, options, report);
  report.seconds_concentrations = since(t0);
  read_lifecycle(root, concentrations.burn_end_s, report);
  root.finish();

  const auto t1 = Clock::now();
  const SpeciesOptics optics = species_optics(material.material, report.wavelengths_um,
                                              material.humidity, options.threads, report.warnings);
  report.seconds_optics = since(t1);
  write_cloud(out_dir, concentrations, optics, output_form, file, options, report);
  report.manifest = out_dir / "cloud.json";
  return report;
}

}  // namespace obscura
