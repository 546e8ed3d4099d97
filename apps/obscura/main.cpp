// obscura: what a visible or infrared sensor sees through obscurant clouds.
#include <fmt/format.h>

#include <iostream>
#include <map>

#include "commands.h"
#include "obscura/core/error.h"
#include "obscura/core/version.h"
#include "obscura/io/provenance.h"

int main(int argc, char** argv) {
  CLI::App app{"obscura: sensor radiance through battlefield obscurant clouds", "obscura"};
  app.set_version_flag("--version", std::string("obscura ") + obscura::kVersion);
  app.require_subcommand(1);
  app.fallthrough(false);

  const obscura::cli::Invocation invocation{obscura::join_command_line(argc, argv)};
  std::map<const CLI::App*, obscura::cli::Runner> runners;
  auto add = [&](obscura::cli::Command c) { runners[c.app] = std::move(c.run); };
  add(obscura::cli::add_info_command(app));
  add(obscura::cli::add_radiance_command(app));
  add(obscura::cli::add_render_command(app, invocation));
  add(obscura::cli::add_make_puff_command(app, invocation));
  add(obscura::cli::add_validate_command(app));
  add(obscura::cli::add_cloud_state_command(app));
  add(obscura::cli::add_mie_command(app));
  add(obscura::cli::add_optics_command(app));
  add(obscura::cli::add_prepare_command(app, invocation));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (auto* sub : app.get_subcommands()) return runners.at(sub)();
  } catch (const obscura::Error& e) {
    std::cerr << "obscura: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "obscura: internal error: " << e.what() << "\n";
    return 2;
  }
  return 1;
}
