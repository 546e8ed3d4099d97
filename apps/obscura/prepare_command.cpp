// `obscura prepare`: particle concentrations (built-in dispersion model or CFD
// output) and a material's optics become cloud keyframes and a manifest.
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "memory_option.h"
#include "obscura/prep/prepare.h"

namespace obscura::cli {

Command add_prepare_command(CLI::App& app, const Invocation& invocation) {
  auto* cmd =
      app.add_subcommand("prepare",
                         "Turn particle concentrations over time (dispersion model, VTK or "
                         "NetCDF-CF) and a material's "
                         "optics into cloud keyframes and a manifest (docs/preparation.md)");
  struct Options {
    std::string config, out;
    int threads = 0;
    bool json = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("config", o->config, "Preparation configuration (JSON)")->required();
  cmd->add_option("-o,--output", o->out, "Folder to create for the keyframes and cloud.json")
      ->required();
  cmd->add_option("--threads", o->threads, "Threads (0: all cores)")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print a JSON summary instead of text");
  cmd->add_flag("-q,--quiet", o->quiet, "No progress on stderr");
  auto max_memory = std::make_shared<std::string>();
  add_max_memory_option(cmd, max_memory);
  return {cmd, [o, &invocation, max_memory]() {
            apply_max_memory(*max_memory);
            PrepareOptions options;
            options.threads = o->threads;
            options.command_line = invocation.command_line;
            if (!o->quiet)
              options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
            const PrepareReport r = prepare_cloud(o->config, o->out, options);
            nlohmann::json j = {{"manifest", r.manifest.string()},
                                {"keyframes", r.keyframes.size()},
                                {"times_s", r.times_s},
                                {"dims", {r.dims.nx, r.dims.ny, r.dims.nz}},
                                {"voxel_size_m", r.voxel_size_m},
                                {"material", r.material},
                                {"output_form", r.output_form},
                                {"wavelengths_um", r.wavelengths_um},
                                {"lifecycle",
                                 {{"init_end", r.lifecycle.init_end},
                                  {"loop_start", r.lifecycle.loop_start},
                                  {"loop_end", r.lifecycle.loop_end},
                                  {"loop_wrap", r.lifecycle.loop_wrap_s},
                                  {"extinction_start", r.lifecycle.extinction_start},
                                  {"suggested", r.lifecycle_suggested}}},
                                {"released_mass_g", r.released_mass_g},
                                {"bytes_written", r.bytes_written},
                                {"seconds",
                                 {{"concentrations", r.seconds_concentrations},
                                  {"optics", r.seconds_optics},
                                  {"keyframes", r.seconds_keyframes}}},
                                {"warnings", r.warnings}};
            if (o->json) {
              std::cout << j.dump(2) << "\n";
              return 0;
            }
            std::cout << fmt::format(
                "{} keyframes of {}×{}×{} voxels ({} m), {} at {} wavelengths, {:.1f} MB{}\n",
                r.keyframes.size(), r.dims.nx, r.dims.ny, r.dims.nz, r.voxel_size_m, r.material,
                r.wavelengths_um.size(), r.bytes_written / 1e6,
                r.output_form == "species" ? " (compact species form)" : "");
            std::cout << fmt::format(
                "times {}–{} s; lifecycle ({}): init_end {}, loop {}–{} (wrap {} s), "
                "extinction from {}\n",
                r.times_s.front(), r.times_s.back(), r.lifecycle_suggested ? "suggested" : "given",
                r.lifecycle.init_end, r.lifecycle.loop_start, r.lifecycle.loop_end,
                r.lifecycle.loop_wrap_s, r.lifecycle.extinction_start);
            std::cout << fmt::format(
                "time: concentrations {:.2f} s, optics {:.2f} s, keyframes {:.2f} s\n",
                r.seconds_concentrations, r.seconds_optics, r.seconds_keyframes);
            for (const auto& w : r.warnings) std::cout << "note: " << w << "\n";
            std::cout << "wrote " << r.manifest.string() << "\n";
            return 0;
          }};
}

}  // namespace obscura::cli
