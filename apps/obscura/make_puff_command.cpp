// `obscura make-puff`: writes a procedural Gaussian smoke puff as a cloud keyframe.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "obscura/io/provenance.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"

namespace obscura::cli {

Command add_make_puff_command(CLI::App& app, const Invocation& invocation) {
  auto* cmd = app.add_subcommand(
      "make-puff", "Write a Gaussian smoke puff (OpenVDB cloud keyframe) for tests and examples");
  struct Options {
    std::string output;
    std::vector<double> center{0, 0, 0};
    GaussianPuffSpec spec;
    double time_s = 0;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("output", o->output, "Output .vdb file")->required();
  cmd->add_option("--center", o->center, "Centre x,y,z in metres")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  cmd->add_option("--radius", o->spec.radius_m, "Gaussian standard deviation s, metres")
      ->capture_default_str();
  cmd->add_option("--extent", o->spec.extent_radii, "Grid half-width in multiples of s")
      ->capture_default_str();
  cmd->add_option("--resolution", o->spec.resolution, "Voxels along each axis")
      ->capture_default_str();
  cmd->add_option("--wavelengths", o->spec.wavelengths_um, "Spectral samples, micrometres")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--sigma-a", o->spec.peak_sigma_a, "Peak absorption coefficient per sample, 1/m")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--sigma-s", o->spec.peak_sigma_s, "Peak scattering coefficient per sample, 1/m")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--g", o->spec.g, "Henyey-Greenstein asymmetry per sample")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--ambient", o->spec.ambient_temperature_k, "Ambient temperature, K")
      ->capture_default_str();
  cmd->add_option("--excess", o->spec.temperature_excess_k, "Temperature excess at the centre, K")
      ->capture_default_str();
  cmd->add_option("--time", o->time_s, "Keyframe time, seconds after activation")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print a JSON summary");
  return {cmd, [o, invocation]() {
            o->spec.center_m = {o->center[0], o->center[1], o->center[2]};
            const VoxelGrid grid = make_gaussian_puff(o->spec);
            const Provenance prov = make_provenance(invocation.command_line, 0, {});
            write_cloud_keyframe(o->output, grid, o->time_s, {{"provenance", prov.to_string()}});
            const BBox3 b = grid.world_bounds();
            nlohmann::json out = {
                {"output", o->output},
                {"dims", {grid.dims().nx, grid.dims().ny, grid.dims().nz}},
                {"voxel_size_m", grid.placement().voxel_size_m},
                {"bounds_m", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
                {"wavelengths_um", grid.wavelengths_um()},
                {"memory_bytes", grid.memory_bytes()}};
            if (o->json) {
              std::cout << out.dump(2) << "\n";
            } else {
              std::cout << fmt::format(
                  "wrote {}: {}³ voxels of {:.4g} m, bounds [{:.4g}, {:.4g}, {:.4g}]–[{:.4g}, "
                  "{:.4g}, {:.4g}] m, wavelengths {} µm\n",
                  o->output, grid.dims().nx, grid.placement().voxel_size_m, b.lo.x, b.lo.y, b.lo.z,
                  b.hi.x, b.hi.y, b.hi.z, fmt::join(grid.wavelengths_um(), ", "));
            }
            return 0;
          }};
}

}  // namespace obscura::cli
