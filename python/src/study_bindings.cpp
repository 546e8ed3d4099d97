// The study layer in Python: obscura.study runs a parameter study (a study
// file, or a dict with its content; docs/studies.md) into an output folder,
// as `obscura study` does in one process, writes the same table (results.csv,
// results.json, …) and returns results.json's content.
#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fstream>
#include <optional>

#include "bindings.h"
#include "long_call.h"
#include "obscura/io/provenance.h"
#include "obscura/study/study_runner.h"
#include "obscura/study/study_table.h"
#include "scene_handle.h"

namespace obscura::python {

void bind_study(py::module_& m) {
  m.def(
      "_study",
      [](const py::object& study, const std::filesystem::path& out,
         const std::optional<std::filesystem::path>& path, std::optional<int> threads, bool resume,
         const py::object& progress, const std::string& command_line) {
        if (threads && *threads < 0) throw InputError("", "threads", "must be >= 0 (0: all cores)");
        const JsonArgument study_file = json_argument(study, path, "study.json");
        const StudySpec spec = parse_study(study_file.doc, study_file.file);
        LongCall call(progress);
        StudyOptions options;
        options.threads = threads.value_or(0);
        options.resume = resume;
        // One line per case, as the CLI prints it; the preparation's lines too.
        options.on_case = [&](const StudyCase& c, const CaseResult& r) {
          call.report_line(fmt::format("{} {}/{} ({}) {} in {:.1f} s{}", c.id, c.index + 1,
                                       spec.case_count, describe_case(spec, c),
                                       r.resumed ? "resumed" : "done", r.seconds,
                                       r.ok ? "" : ": failed: " + r.error));
        };
        options.progress = [&](const std::string& line) { call.report_line(line); };
        const std::vector<std::filesystem::path> written = call.run([&] {
          const StudyResult result = run_study(spec, out, options);
          // A dict's study file does not exist: the documents it names do.
          std::vector<std::filesystem::path> inputs;
          for (const auto& f : {spec.file, spec.prepare_path, spec.scene_path})
            if (!f.empty() && std::filesystem::is_regular_file(f)) inputs.push_back(f);
          return write_study_results(spec, result, out, make_provenance(command_line, 0, inputs));
        });
        std::ifstream in(out / "results.json");
        py::dict results = json_to_python(nlohmann::json::parse(in));
        results["files"] = py::cast(written);
        return results;
      },
      py::arg("study"), py::arg("out"), py::arg("path"), py::arg("threads"), py::arg("resume"),
      py::arg("progress"), py::arg("command_line"));
}

}  // namespace obscura::python
