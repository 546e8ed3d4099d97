#pragma once
// Runs a parameter study (study/study_spec.h) into an output folder: every
// case prepared (when the study has a preparation), rendered over the study's
// times and measured (screening metrics of the scene's target), its result
// stored as cases/<id>/result.json. A case that fails is recorded with its
// error and the study goes on. With `resume`, a case whose stored result is
// complete and was made from the same documents is not run again, so an
// interrupted study loses only the cases that were running.
//
// Shared among processes (core/process_group.h): each process takes the next
// case no other has claimed (a claim file in <out>/.claims, so the output
// folder must be on a file system every process sees) and runs it with all
// of its threads; rank 0 gathers every result. A case's numbers do not
// depend on where it ran.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/study/study_spec.h"

namespace obscura {

// The screening of one sensor's band over a case's frames
// (analysis/screening_metrics.h); empty optionals: never screened.
struct CaseSeries {
  std::string sensor, band;
  std::optional<double> time_to_screen_s, screening_duration_s;
  std::optional<double> screened_from_s, screened_until_s;
  double min_transmittance = 0;  // the lowest frame mean over the target, 1
  double max_screened_fraction = 0;
};

struct CaseResult {
  std::size_t index = 0;
  std::string id;
  bool ok = false;
  std::string error;     // when not ok
  double seconds = 0;    // wall time of the case, where it ran
  int rank = 0;          // the process that ran it
  bool resumed = false;  // read back from an earlier run
  std::string fingerprint;
  std::vector<CaseSeries> series;
};

struct StudyOptions {
  int threads = 0;  // per process; 0: all cores
  bool resume = false;
  const ProcessGroup* processes = &single_process();
  // On the process that ran (or resumed) a case, when it is done.
  std::function<void(const StudyCase&, const CaseResult&)> on_case;
  // Lines of progress from inside a case (the preparation's), may be empty.
  std::function<void(const std::string&)> progress;
};

struct StudyResult {
  std::vector<CaseResult> cases;  // on rank 0: every case, in case order
  std::size_t failed = 0, resumed = 0;
  double seconds = 0;
};

// Every process of the group calls it. The output folder must not exist or
// be empty, unless `resume`. Throws InputError for a folder that cannot be
// used; a case's failure is recorded instead.
StudyResult run_study(const StudySpec& spec, const std::filesystem::path& out_dir,
                      const StudyOptions& options = {});

// A case's stored result (result.json), as written by run_study.
nlohmann::json case_result_json(const CaseResult& r);
CaseResult case_result_from_json(const nlohmann::json& j);

}  // namespace obscura
