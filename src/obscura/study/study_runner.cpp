#include "obscura/study/study_runner.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/json_reader.h"
#include "obscura/prep/prepare.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
std::optional<double> optional_from(const nlohmann::json& v) {
  if (v.is_null()) return std::nullopt;
  return v.get<double>();
}

CaseSeries case_series(const ScreeningSeries& s) {
  CaseSeries c;
  c.sensor = s.sensor;
  c.band = s.band.name();
  c.time_to_screen_s = s.screening.time_to_screen_s;
  c.screening_duration_s = s.screening.screening_duration_s;
  c.screened_from_s = s.screening.screened_from_s;
  c.screened_until_s = s.screening.screened_until_s;
  c.min_transmittance = s.min_transmittance_mean;
  c.max_screened_fraction = s.max_screened_fraction;
  return c;
}

// One case where it runs: documents, preparation, render, measurement.
CaseResult run_case(const StudySpec& spec, const StudyCase& c, const fs::path& case_dir,
                    const CaseDocuments& docs, const StudyOptions& options) {
  CaseResult r;
  r.index = c.index;
  r.id = c.id;
  r.fingerprint = docs.fingerprint;
  const auto start = Clock::now();
  try {
    // What ran, for a user to look at or render again.
    if (!spec.prepare_path.empty())
      write_text_file_atomic(case_dir / "prepare.json", docs.prepare.dump(2) + "\n");
    write_text_file_atomic(case_dir / "scene.json", docs.scene.dump(2) + "\n");
    const fs::path cloud = case_dir / "cloud";
    fs::remove_all(cloud);  // an earlier, interrupted try
    if (!spec.prepare_path.empty()) {
      PrepareOptions prepare;
      prepare.threads = options.threads;
      prepare.progress = options.progress;
      prepare.command_line = "obscura study " + spec.file.string() + " (" + c.id + ")";
      prepare_cloud(docs.prepare, spec.prepare_path, cloud, prepare);
    }
    Scene scene = parse_scene(docs.scene, spec.scene_path);
    scene.settings.threads = options.threads;
    const SequenceResult sequence = render_sequence(scene, spec.times_s);
    for (const ScreeningSeries& s : sequence.series) r.series.push_back(case_series(s));
    if (!spec.keep_clouds) fs::remove_all(cloud);
    r.ok = true;
  } catch (const Interrupted&) {
    throw;  // not the case's failure: the study stops, and --resume runs the case again
  } catch (const InternalError& e) {
    r.error = std::string("internal error: ") + e.what();
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.seconds = seconds_since(start);
  return r;
}

// A stored result this case can reuse: complete and from the same documents.
std::optional<CaseResult> stored_result(const fs::path& file, const std::string& fingerprint) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  try {
    CaseResult r = case_result_from_json(read_json_file(file.string()));
    if (!r.ok || r.fingerprint != fingerprint) return std::nullopt;
    r.resumed = true;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: run the case again
  }
}

fs::path claims_folder(const fs::path& out_dir) { return out_dir / ".claims"; }

// Whether this process takes case i. Alone, it takes every case. Shared,
// the first process to create the case's claim file (O_EXCL: atomic, on NFS
// too) takes it, so a process that finishes early takes the next free case
// and cases of unequal cost do not leave processes idle; which process ran a
// case does not change its numbers.
bool claim_case(const fs::path& out_dir, std::size_t index, const ProcessGroup& group) {
  if (group.size() == 1) return true;
  const fs::path claim = claims_folder(out_dir) / fmt::format("case_{:04d}", index);
  const int fd = ::open(claim.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw Error(
        fmt::format("{}: cannot create a claim file: {}", claim.string(), std::strerror(errno)));
  }
  const std::string rank = std::to_string(group.rank()) + "\n";
  [[maybe_unused]] const auto written = ::write(fd, rank.data(), rank.size());
  ::close(fd);
  return true;
}

void check_output_folder(const fs::path& out_dir, bool resume) {
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec))
    throw InputError(out_dir.string(), "", "exists and is not a folder");
  if (!resume && fs::exists(out_dir, ec) && !fs::is_empty(out_dir, ec))
    throw InputError(out_dir.string(), "",
                     "exists and is not empty: use --resume to continue the study in it, or "
                     "choose another folder");
  fs::create_directories(out_dir / "cases");
}

}  // namespace

nlohmann::json case_result_json(const CaseResult& r) {
  nlohmann::json series = nlohmann::json::array();
  for (const CaseSeries& s : r.series)
    series.push_back({{"sensor", s.sensor},
                      {"band", s.band},
                      {"time_to_screen_s", optional_json(s.time_to_screen_s)},
                      {"screening_duration_s", optional_json(s.screening_duration_s)},
                      {"screened_from_s", optional_json(s.screened_from_s)},
                      {"screened_until_s", optional_json(s.screened_until_s)},
                      {"min_transmittance", s.min_transmittance},
                      {"max_screened_fraction", s.max_screened_fraction}});
  return {{"case", r.index},
          {"id", r.id},
          {"status", r.ok ? "ok" : "failed"},
          {"error", r.ok ? nlohmann::json(nullptr) : nlohmann::json(r.error)},
          {"seconds", r.seconds},
          {"rank", r.rank},
          {"fingerprint", r.fingerprint},
          {"series", series}};
}

CaseResult case_result_from_json(const nlohmann::json& j) {
  CaseResult r;
  r.index = j.at("case").get<std::size_t>();
  r.id = j.at("id").get<std::string>();
  r.ok = j.at("status").get<std::string>() == "ok";
  if (!r.ok) r.error = j.at("error").get<std::string>();
  r.seconds = j.at("seconds").get<double>();
  r.rank = j.at("rank").get<int>();
  r.fingerprint = j.at("fingerprint").get<std::string>();
  for (const nlohmann::json& s : j.at("series")) {
    CaseSeries c;
    c.sensor = s.at("sensor").get<std::string>();
    c.band = s.at("band").get<std::string>();
    c.time_to_screen_s = optional_from(s.at("time_to_screen_s"));
    c.screening_duration_s = optional_from(s.at("screening_duration_s"));
    c.screened_from_s = optional_from(s.at("screened_from_s"));
    c.screened_until_s = optional_from(s.at("screened_until_s"));
    // NaN (no target pixel in view) is stored as null.
    c.min_transmittance = s.at("min_transmittance").is_null()
                              ? std::nan("")
                              : s.at("min_transmittance").get<double>();
    c.max_screened_fraction = s.at("max_screened_fraction").is_null()
                                  ? std::nan("")
                                  : s.at("max_screened_fraction").get<double>();
    r.series.push_back(std::move(c));
  }
  return r;
}

StudyResult run_study(const StudySpec& spec, const fs::path& out_dir, const StudyOptions& options) {
  const ProcessGroup& group = *options.processes;
  const auto start = Clock::now();
  run_together(group, [&] {
    if (group.is_root()) {
      check_output_folder(out_dir, options.resume);
      // Claims of an earlier, interrupted run are void.
      fs::remove_all(claims_folder(out_dir));
      if (group.size() > 1) fs::create_directories(claims_folder(out_dir));
    }
  });
  // This process's cases, each with its result stored where it ran. A
  // failure outside a case (the folder cannot be written) ends the study on
  // every process, after each has finished its case.
  std::vector<std::string> mine;
  std::exception_ptr failure;
  try {
    for (std::size_t i = 0; i < spec.case_count; ++i) {
      throw_if_interrupted();
      if (!claim_case(out_dir, i, group)) continue;
      const StudyCase c = study_case(spec, i);
      const fs::path case_dir = out_dir / "cases" / c.id;
      const CaseDocuments docs = case_documents(spec, c, case_dir / "cloud" / "cloud.json");
      std::optional<CaseResult> r;
      if (options.resume) r = stored_result(case_dir / "result.json", docs.fingerprint);
      if (!r) {
        fs::create_directories(case_dir);
        r = run_case(spec, c, case_dir, docs, options);
        r->rank = group.rank();
        write_text_file_atomic(case_dir / "result.json", case_result_json(*r).dump(2) + "\n");
      }
      if (options.on_case) options.on_case(c, *r);
      nlohmann::json message = case_result_json(*r);
      message["resumed"] = r->resumed;
      mine.push_back(message.dump());
    }
  } catch (...) {
    failure = std::current_exception();
  }
  share_failure(group, failure);
  // Every result to rank 0, in case order.
  ByteWriter out;
  out.put<std::uint64_t>(mine.size());
  for (const std::string& m : mine) out.put_string(m);
  const std::vector<std::string> all = group.gather(out.take());
  StudyResult result;
  if (group.is_root()) {
    std::vector<std::optional<CaseResult>> by_case(spec.case_count);
    for (const std::string& bytes : all) {
      ByteReader in(bytes);
      const auto n = in.get<std::uint64_t>();
      for (std::uint64_t k = 0; k < n; ++k) {
        const nlohmann::json message = nlohmann::json::parse(in.get_string());
        CaseResult c = case_result_from_json(message);
        c.resumed = message.at("resumed").get<bool>();
        OBSCURA_CHECK_MSG(c.index < spec.case_count && !by_case[c.index], "a case ran twice");
        by_case[c.index] = std::move(c);
      }
    }
    for (std::optional<CaseResult>& c : by_case) {
      OBSCURA_CHECK_MSG(c.has_value(), "a case did not run");
      result.cases.push_back(std::move(*c));
    }
    std::error_code ec;
    fs::remove_all(claims_folder(out_dir), ec);
  }
  for (const CaseResult& c : result.cases) {
    result.failed += c.ok ? 0 : 1;
    result.resumed += c.resumed ? 1 : 0;
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace obscura
