// `obscura info`: what a cloud keyframe file holds.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "obscura/io/vdb_keyframe.h"

namespace obscura::cli {

namespace {

nlohmann::json info_json(const KeyframeInfo& info) {
  const GridPlacement& p = info.placement;
  const BBox3& b = info.world_bounds_m;
  nlohmann::json out = {{"file", info.file.string()},
                        {"file_bytes", info.file_bytes},
                        {"form", info.form},
                        {"dims", {info.dims.nx, info.dims.ny, info.dims.nz}},
                        {"voxels", info.dims.count()},
                        {"voxel_size_m", p.voxel_size_m},
                        {"origin_m", {p.origin_m.x, p.origin_m.y, p.origin_m.z}},
                        {"rotation",
                         {{p.rotation.m[0][0], p.rotation.m[0][1], p.rotation.m[0][2]},
                          {p.rotation.m[1][0], p.rotation.m[1][1], p.rotation.m[1][2]},
                          {p.rotation.m[2][0], p.rotation.m[2][1], p.rotation.m[2][2]}}},
                        {"bounds_m", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
                        {"time_s", info.time_s},
                        {"wavelengths_um", info.wavelengths_um},
                        {"spectral_samples", info.wavelengths_um.size()},
                        {"memory_bytes", info.memory_bytes},
                        {"metadata", info.metadata},
                        {"channels", nlohmann::json::array()}};
  for (const auto& c : info.channels)
    out["channels"].push_back({{"name", c.name},
                               {"units", c.units},
                               {"min", c.min},
                               {"max", c.max},
                               {"nonzero_voxels", c.nonzero_voxels}});
  if (info.form == "species") {
    out["compact_bytes"] = info.compact_bytes;
    out["species"] = nlohmann::json::array();
    for (const auto& sp : info.species)
      out["species"].push_back({{"name", sp.optics.name},
                                {"mass_absorption_m2_g", sp.optics.mass_absorption_m2_g},
                                {"mass_scattering_m2_g", sp.optics.mass_scattering_m2_g},
                                {"asymmetry", sp.optics.asymmetry},
                                {"concentration",
                                 {{"name", sp.concentration.name},
                                  {"units", sp.concentration.units},
                                  {"min", sp.concentration.min},
                                  {"max", sp.concentration.max},
                                  {"nonzero_voxels", sp.concentration.nonzero_voxels}}}});
  }
  return out;
}

std::string info_text(const KeyframeInfo& info) {
  const GridPlacement& p = info.placement;
  const BBox3& b = info.world_bounds_m;
  std::ostringstream out;
  out << fmt::format("{} ({:.1f} KiB)\n", info.file.string(), info.file_bytes / 1024.0);
  out << fmt::format("  grid         {} x {} x {} voxels of {:.6g} m ({} voxels)\n", info.dims.nx,
                     info.dims.ny, info.dims.nz, p.voxel_size_m, info.dims.count());
  out << fmt::format("  bounds       [{:.4g}, {:.4g}, {:.4g}] – [{:.4g}, {:.4g}, {:.4g}] m\n",
                     b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
  out << fmt::format("  origin       [{:.6g}, {:.6g}, {:.6g}] m{}\n", p.origin_m.x, p.origin_m.y,
                     p.origin_m.z, p.rotation == Mat3::identity() ? "" : " (rotated grid)");
  out << fmt::format("  time         {:.6g} s after activation\n", info.time_s);
  out << fmt::format("  wavelengths  {} µm ({} spectral samples)\n",
                     fmt::join(info.wavelengths_um, ", "), info.wavelengths_um.size());
  if (info.form == "species") {
    out << fmt::format("  form         compact species form: {} species, expanded on reading\n",
                       info.species.size());
    out << fmt::format(
        "  memory       {:.1f} MiB dense once expanded ({:.1f} MiB of concentration and "
        "temperature)\n",
        info.memory_bytes / 1048576.0, info.compact_bytes / 1048576.0);
    for (std::size_t i = 0; i < info.species.size(); ++i) {
      const SpeciesOptics& sp = info.species[i].optics;
      const ChannelSummary& c = info.species[i].concentration;
      out << fmt::format("  species {:<4} {}: {} ({}) {:.5g} – {:.5g}, {} non-zero voxels\n", i,
                         sp.name, c.name, c.units, c.min, c.max, c.nonzero_voxels);
      out << "      λ (µm)  k_abs (m2/g)  k_sca (m2/g)         g\n";
      for (std::size_t k = 0; k < sp.wavelengths_um.size(); ++k)
        out << fmt::format("  {:>10.6g} {:>13.5g} {:>13.5g} {:>9.4g}\n", sp.wavelengths_um[k],
                           sp.mass_absorption_m2_g[k], sp.mass_scattering_m2_g[k], sp.asymmetry[k]);
    }
  } else {
    out << "  form         spectral (σa, σs, g per wavelength)\n";
    out << fmt::format("  memory       {:.1f} MiB dense in memory\n",
                       info.memory_bytes / 1048576.0);
  }
  out << "  channel         units        min          max    non-zero voxels\n";
  for (const auto& c : info.channels)
    out << fmt::format("  {:<14} {:<5} {:>12.5g} {:>12.5g} {:>18}\n", c.name, c.units, c.min, c.max,
                       c.nonzero_voxels);
  return out.str();
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info",
                                 "Describe a cloud keyframe (.vdb): form, grid, bounds, spectral "
                                 "samples, species, value ranges, memory");
  struct Options {
    std::string file;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("file", o->file, "Cloud keyframe (OpenVDB file, docs/formats.md)")->required();
  cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
  return {cmd, [o]() {
            const KeyframeInfo info = inspect_cloud_keyframe(o->file);
            if (o->json)
              std::cout << info_json(info).dump(2) << "\n";
            else
              std::cout << info_text(info);
            return 0;
          }};
}

}  // namespace obscura::cli
