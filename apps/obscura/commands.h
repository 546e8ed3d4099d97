#pragma once
// Subcommands of the `obscura` tool. Each registers its options on the parent
// app and returns the function that runs it (exit status). Commands are thin:
// they parse, call the library and print (docs/conventions.md §16).
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "obscura/core/process_group.h"

namespace obscura::cli {

using Runner = std::function<int()>;

struct Command {
  CLI::App* app;
  Runner run;
};

// The full command line, recorded in provenance, and the processes the run
// is shared among (one without an MPI launcher; cluster/process_world.h).
struct Invocation {
  std::string command_line;
  const ProcessGroup* processes = &single_process();
};

Command add_info_command(CLI::App& app);
Command add_radiance_command(CLI::App& app);
Command add_render_command(CLI::App& app, const Invocation& invocation);
Command add_make_puff_command(CLI::App& app, const Invocation& invocation);
Command add_validate_command(CLI::App& app);
Command add_cloud_state_command(CLI::App& app);
Command add_mie_command(CLI::App& app);
Command add_optics_command(CLI::App& app);
Command add_prepare_command(CLI::App& app, const Invocation& invocation);
Command add_study_command(CLI::App& app, const Invocation& invocation);

}  // namespace obscura::cli
