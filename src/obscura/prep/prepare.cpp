#include "obscura/prep/prepare.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <variant>

#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/io/cloud_manifest.h"
#include "obscura/io/json_reader.h"
#include "obscura/io/netcdf_cf.h"
#include "obscura/io/stale_temporaries.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/medium/voxelise.h"
#include "obscura/optics/material.h"
#include "obscura/optics/material_species_optics.h"
#include "obscura/prep/dispersion/dispersion_grid.h"
#include "obscura/prep/prepare_config.h"
#include "obscura/prep/suggested_lifecycle.h"

namespace obscura {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
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

// Concentrations over time, from the configuration's source, and what the
// keyframes need to know of their origin.
struct Concentrations {
  ConcentrationSeries series;
  std::optional<double> burn_end_s;  // dispersion: when the last device stops
  double ambient_k = 288.15;
};

Concentrations concentrations_of(const DispersionSource& s, const PrepareOptions& options,
                                 PrepareReport& report) {
  Concentrations c;
  c.ambient_k = s.config.ambient_temperature_k;
  double end = 0;
  for (const SmokeDevice& d : s.config.devices) {
    end = std::max(end, d.start_s + d.burn_time_s);
    report.released_mass_g += d.released_mass_g();
  }
  c.burn_end_s = end;
  say(options, fmt::format("dispersion: {} devices, {} frames from {} to {} s at {} m voxels",
                           s.config.devices.size(), s.times_s.size(), s.times_s.front(),
                           s.times_s.back(), s.voxel_size_m));
  c.series = dispersion_series(s.config, s.times_s, s.voxel_size_m, options.threads);
  return c;
}

Concentrations concentrations_of(const VtkSource& s, const PrepareOptions& options,
                                 PrepareReport&) {
  Concentrations c;
  c.ambient_k = s.ambient_temperature_k;
  say(options, fmt::format("VTK: {} frames", s.time_and_path.size()));
  c.series = read_vtk_series(s.time_and_path, s.names);
  return c;
}

Concentrations concentrations_of(const NetcdfSource& s, const PrepareOptions& options,
                                 PrepareReport&) {
  Concentrations c;
  c.ambient_k = s.ambient_temperature_k;
  say(options, "NetCDF: " + s.file.string());
  c.series = read_netcdf_cf(s.file, s.options);
  return c;
}

// The source's frames; at least two. Fills in the report's times and grid.
Concentrations read_concentrations(const PrepareConfig& config, const PrepareOptions& options,
                                   PrepareReport& report) {
  Concentrations c =
      std::visit([&](const auto& source) { return concentrations_of(source, options, report); },
                 config.source);
  if (c.series.frames.size() < 2)
    throw InputError(config.file, "/source",
                     "needs at least two frames (a lifecycle needs two keyframes)");
  for (const auto& f : c.series.frames) report.times_s.push_back(f.time_s);
  report.dims = c.series.frames[0].concentration_g_m3.dims;
  report.voxel_size_m = c.series.frames[0].concentration_g_m3.placement.voxel_size_m;
  return c;
}

// The lifecycle: given, or suggested from the timing; validated.
void settle_lifecycle(const PrepareConfig& config, std::optional<double> burn_end_s,
                      PrepareReport& report) {
  report.lifecycle_suggested = !config.lifecycle;
  report.lifecycle =
      config.lifecycle ? *config.lifecycle : suggest_lifecycle(report.times_s, burn_end_s);
  Lifecycle(report.times_s, report.lifecycle, config.file + ": /lifecycle");  // validates
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
  if (fs::exists(out_dir) && !(fs::is_directory(out_dir) && fs::is_empty(out_dir)))
    throw InputError(out_dir.string(), "",
                     "exists and is not an empty folder; remove it or choose another");
  const PrepareConfig config = read_prepare_config(doc, config_path);
  PrepareReport report;
  report.material = config.material.name;
  report.wavelengths_um = config.wavelengths_um;
  report.output_form = config.output_form;

  const auto t0 = Clock::now();
  const Concentrations concentrations = read_concentrations(config, options, report);
  report.seconds_concentrations = since(t0);
  settle_lifecycle(config, concentrations.burn_end_s, report);

  const auto t1 = Clock::now();
  const SpeciesOptics optics =
      material_species_optics(config.material, report.wavelengths_um, config.relative_humidity,
                              options.threads, report.warnings);
  report.seconds_optics = since(t1);
  write_cloud(out_dir, concentrations, optics, config.output_form, config.file, options, report);
  report.manifest = out_dir / "cloud.json";
  return report;
}

}  // namespace obscura
