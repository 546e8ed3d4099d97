// `obscura cloud-state`: the lifecycle phase, keyframes, weight and pose of a
// time-varying cloud at one time, from its manifest alone (no keyframe is read).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "obscura/core/error.h"
#include "obscura/io/cloud_manifest.h"

namespace obscura::cli {

Command add_cloud_state_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "cloud-state",
      "Lifecycle phase, interpolated keyframes and trajectory pose of a cloud manifest at a time");
  struct Options {
    std::string manifest;
    double at = 0;
    double activate = 0;
    std::optional<double> deactivate;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("manifest", o->manifest, "Cloud manifest (JSON)")->required();
  cmd->add_option("--at", o->at, "Scene time, s")->required();
  cmd->add_option("--activate", o->activate, "Activation time, s (default 0)");
  cmd->add_option("--deactivate", o->deactivate, "Deactivation time, s (default: never)");
  cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
  return {cmd, [o]() {
            if (!std::isfinite(o->at)) throw InputError("", "--at", "must be a finite time, s");
            if (!std::isfinite(o->activate))
              throw InputError("", "--activate", "must be a finite time, s");
            if (o->deactivate && std::isnan(*o->deactivate))
              throw InputError("", "--deactivate", "must be a time, s");
            const CloudManifest m = read_cloud_manifest(o->manifest);
            const LifecycleState s = m.lifecycle.at(o->at, o->activate, o->deactivate);
            const TrajectoryPose p = m.trajectory.at(s.local_time_s);
            if (o->json) {
              nlohmann::json out;
              out["phase"] = to_string(s.phase);
              out["keyframes"] = {s.keyframe0, s.keyframe1};
              out["weight"] = s.weight;
              out["local_time_s"] = s.local_time_s;
              out["position_m"] = {p.position_m.x, p.position_m.y, p.position_m.z};
              out["heading_deg"] = p.heading_deg;
              std::cout << out.dump(2) << "\n";
            } else {
              // Nine significant digits: readable, and far below any time step that matters
              // (--json prints every digit).
              std::cout << fmt::format("phase       {}\n", to_string(s.phase))
                        << fmt::format("keyframes   {} {}\n", s.keyframe0, s.keyframe1)
                        << fmt::format("weight      {:.9g}\n", s.weight)
                        << fmt::format("local time  {:.9g} s\n", s.local_time_s)
                        << fmt::format("position    {:.9g} {:.9g} {:.9g} m\n", p.position_m.x,
                                       p.position_m.y, p.position_m.z)
                        << fmt::format("heading     {:.9g} deg\n", p.heading_deg);
            }
            return 0;
          }};
}

}  // namespace obscura::cli
