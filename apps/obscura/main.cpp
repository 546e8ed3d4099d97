// obscura: what a visible or infrared sensor sees through obscurant clouds.
#include <fmt/format.h>

#include <iostream>
#include <map>
#include <new>

#include "commands.h"
#include "exit_status.h"
#include "obscura/cluster/process_world.h"
#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/version.h"
#include "obscura/io/provenance.h"

namespace {

// CLI11 exits with its own codes (105, 106, 109, …) and no prefix; every usage
// error gets the tool's prefix and one documented status instead (docs/errors.md).
int usage_error(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  // --help and --version are parse "errors" with status 0: CLI11 prints them.
  if (e.get_exit_code() == 0) return app.exit(e);
  // CLI11 reports an unknown command word only as "a subcommand is required".
  std::string what = e.what();
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
    std::string known;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
      known += (known.empty() ? "" : ", ") + sub->get_name();
    what = fmt::format("'{}' is not a command (expected one of: {})", argv[1], known);
  }
  std::cerr << "obscura: error: " << what << "\n"
            << "run 'obscura --help' or 'obscura <command> --help' for usage\n";
  return obscura::cli::kExitUsage;
}

// A bug, not bad input: say so and ask for a report.
int internal_error(const std::string& what) {
  std::string detail = what;
  if (detail.rfind("internal error: ", 0) == 0) detail.erase(0, 16);
  std::cerr << "obscura: internal error: " << detail << "\n"
            << "this is a bug in obscura; please report it with the command line and the input "
               "files\n";
  return obscura::cli::kExitInternal;
}

// The exit status of a failure, after saying what it was: rank 0 speaks
// for the run; another rank only for a failure it met alone.
int report_failure(const std::exception_ptr& failure, int rank) {
  const std::string who = rank == 0 ? "" : fmt::format(" (rank {})", rank);
  try {
    std::rethrow_exception(failure);
  } catch (const obscura::PeerFailure& e) {
    // Rank 0 reports what failed; this rank ends with the same status.
    return e.internal() ? obscura::cli::kExitInternal : obscura::cli::kExitInputError;
  } catch (const obscura::Interrupted& e) {
    // What completed is kept and was said by the command (a sequence's frames).
    std::cerr << "obscura" << who << ": " << e.what() << "\n";
    return 128 + e.signal();
  } catch (const obscura::InternalError& e) {
    return internal_error(e.what() + who);
  } catch (const obscura::Error& e) {
    std::cerr << "obscura: error" << who << ": " << e.what() << "\n";
    return obscura::cli::kExitInputError;
  } catch (const std::bad_alloc&) {
    // Sizes from files are checked against the memory limit before they are
    // allocated (core/memory_limit.h): an allocation failing anyway is a size
    // nobody checked.
    return internal_error("out of memory in an allocation that was not checked first" + who);
  } catch (const std::exception& e) {
    return internal_error(e.what() + who);
  }
  return obscura::cli::kExitInternal;
}

}  // namespace

int main(int argc, char** argv) {
  obscura::install_interrupt_handlers();
  std::unique_ptr<obscura::ProcessWorld> world;
  try {
    world = std::make_unique<obscura::ProcessWorld>(argc, argv);
  } catch (const obscura::Error& e) {
    std::cerr << "obscura: error: " << e.what() << "\n";
    return obscura::cli::kExitUsage;
  }
  const obscura::ProcessGroup& processes = world->group();

  CLI::App app{"obscura: sensor radiance through battlefield obscurant clouds", "obscura"};
  app.set_version_flag("--version", std::string("obscura ") + obscura::kVersion);
  app.require_subcommand(1);
  app.fallthrough(false);

  const obscura::cli::Invocation invocation{obscura::join_command_line(argc, argv), &processes};
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
  add(obscura::cli::add_study_command(app, invocation));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same command line: rank 0 alone says what is wrong.
    if (!processes.is_root()) return e.get_exit_code() == 0 ? 0 : obscura::cli::kExitUsage;
    return usage_error(app, e, argc, argv);
  }
  std::exception_ptr failure;
  try {
    for (auto* sub : app.get_subcommands()) {
      // Only these share their work among MPI ranks; N copies of any other
      // would write the same files N times.
      if (world->distributed() && sub->get_name() != "render" && sub->get_name() != "study") {
        if (!processes.is_root()) return obscura::cli::kExitUsage;
        std::cerr << "obscura: error: '" << sub->get_name()
                  << "' runs on one process: start it without mpirun (only 'render' and "
                     "'study' share their work among MPI ranks)\n";
        return obscura::cli::kExitUsage;
      }
      return runners.at(sub)();
    }
  } catch (...) {
    failure = std::current_exception();
  }
  if (!failure) return obscura::cli::kExitInputError;
  const int status = report_failure(failure, processes.rank());
  // A failure that every rank knows of ends each cleanly (core/process_group.h);
  // any other may have left ranks waiting in a collective: end them all.
  if (world->distributed() && !obscura::failure_was_shared()) world->abort(status);
  return status;
}
