// `obscura study`: a parameter study over a base preparation and scene
// (study/study_spec.h), its cases shared among MPI ranks when started by
// mpirun, the results gathered into one table (study/study_table.h).
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "exit_status.h"
#include "memory_option.h"
#include "obscura/io/provenance.h"
#include "obscura/study/study_runner.h"
#include "obscura/study/study_table.h"

namespace obscura::cli {
namespace {

// One line per finished case, from the rank that ran it.
void print_case(const StudySpec& spec, const StudyCase& c, const CaseResult& r, int rank,
                int ranks) {
  const std::string who = ranks > 1 ? fmt::format("rank {}/{}: ", rank, ranks) : "";
  std::string what;
  if (!r.ok) {
    what = "failed: " + r.error;
  } else {
    for (const CaseSeries& s : r.series)
      what += fmt::format("{}{} {} {}", what.empty() ? "" : "; ", s.sensor, s.band,
                          s.screening_duration_s && *s.screening_duration_s > 0
                              ? fmt::format("screened {:.3g} s", *s.screening_duration_s)
                              : std::string("not screened"));
  }
  std::cerr << fmt::format("obscura: {}{} {}/{} ({}) {} in {:.1f} s: {}\n", who, c.id, c.index + 1,
                           spec.case_count, describe_case(spec, c), r.resumed ? "resumed" : "done",
                           r.seconds, what);
}

}  // namespace

Command add_study_command(CLI::App& app, const Invocation& invocation) {
  auto* cmd = app.add_subcommand(
      "study",
      "Run a parameter study: every case of a base preparation and scene with the study's axes "
      "set, prepared, rendered and measured; one table of results (docs/studies.md)");
  struct Options {
    std::string study, out;
    std::optional<int> threads;
    bool resume = false, json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("study", o->study, "Study file (JSON, docs/studies.md)")->required();
  cmd->add_option("-o,--output", o->out,
                  "Output folder: results.csv, results.json, screening.png and cases/<id>/")
      ->required();
  cmd->add_option("--threads", o->threads, "Threads per process (0: all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->add_flag("--resume", o->resume,
                "Continue a study in its output folder: cases whose results are complete (and "
                "made from the same files) are not run again");
  cmd->add_flag("--json", o->json, "Print the results (results.json) on stdout");
  auto max_memory = std::make_shared<std::string>();
  add_max_memory_option(cmd, max_memory);
  return {cmd, [o, invocation, max_memory]() {
            const ProcessGroup& processes = *invocation.processes;
            apply_max_memory(*max_memory);
            std::optional<StudySpec> spec;
            run_together(processes, [&] { spec.emplace(load_study(o->study)); });
            if (processes.is_root())
              std::cerr << fmt::format("obscura: study {}: {} cases of {} frames on {} process{}\n",
                                       o->study, spec->case_count, spec->times_s.size(),
                                       processes.size(), processes.size() > 1 ? "es" : "");
            StudyOptions options;
            options.threads = o->threads.value_or(0);
            options.resume = o->resume;
            options.processes = &processes;
            options.on_case = [&](const StudyCase& c, const CaseResult& r) {
              print_case(*spec, c, r, processes.rank(), processes.size());
            };
            const StudyResult result = run_study(*spec, o->out, options);
            std::vector<std::filesystem::path> written;
            run_together(processes, [&] {
              if (!processes.is_root()) return;
              std::vector<std::filesystem::path> inputs;
              for (const auto& f : {spec->file, spec->prepare_path, spec->scene_path})
                if (!f.empty()) inputs.push_back(f);
              const Provenance provenance = make_provenance(invocation.command_line, 0, inputs);
              written = write_study_results(*spec, result, o->out, provenance);
            });
            const int status = result.failed > 0 ? kExitCasesFailed : 0;
            if (!processes.is_root()) return status;
            if (o->json) {
              std::ifstream in(std::filesystem::path(o->out) / "results.json");
              std::cout << in.rdbuf();
              return status;
            }
            std::cout << fmt::format("{} cases: {} ok, {} failed, {} resumed, in {:.1f} s\n",
                                     result.cases.size(), result.cases.size() - result.failed,
                                     result.failed, result.resumed, result.seconds);
            for (const CaseResult& c : result.cases)
              if (!c.ok) std::cout << fmt::format("  {} failed: {}\n", c.id, c.error);
            std::cout << "wrote";
            for (const auto& f : written) std::cout << " " << f.string();
            std::cout << "\n";
            return status;
          }};
}

}  // namespace obscura::cli
