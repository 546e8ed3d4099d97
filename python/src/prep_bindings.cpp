// The preparation layer in Python: obscura.prepare turns a `prepare`
// configuration (a file or a dict with its content, docs/preparation.md)
// into cloud keyframes and a manifest, as `obscura prepare` does, and returns
// what `obscura prepare --json` prints.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "bindings.h"
#include "long_call.h"
#include "obscura/prep/prepare.h"
#include "scene_handle.h"

namespace obscura::python {
namespace {

py::dict report_dict(const PrepareReport& r) {
  py::dict d;
  d["manifest"] = r.manifest;
  d["keyframes"] = py::cast(r.keyframes);
  d["times_s"] = py::cast(r.times_s);
  d["dims"] = py::make_tuple(r.dims.nx, r.dims.ny, r.dims.nz);
  d["voxel_size_m"] = r.voxel_size_m;
  d["material"] = r.material;
  d["output_form"] = r.output_form;
  d["wavelengths_um"] = py::cast(r.wavelengths_um);
  py::dict lifecycle;
  lifecycle["init_end"] = r.lifecycle.init_end;
  lifecycle["loop_start"] = r.lifecycle.loop_start;
  lifecycle["loop_end"] = r.lifecycle.loop_end;
  lifecycle["loop_wrap"] = r.lifecycle.loop_wrap_s;
  lifecycle["extinction_start"] = r.lifecycle.extinction_start;
  lifecycle["suggested"] = r.lifecycle_suggested;
  d["lifecycle"] = lifecycle;
  d["released_mass_g"] = r.released_mass_g;
  d["bytes_written"] = r.bytes_written;
  d["seconds"] =
      py::dict(py::arg("concentrations") = r.seconds_concentrations,
               py::arg("optics") = r.seconds_optics, py::arg("keyframes") = r.seconds_keyframes);
  d["warnings"] = py::cast(r.warnings);
  return d;
}

}  // namespace

void bind_prep(py::module_& m) {
  m.def(
      "_prepare",
      [](const py::object& config, const std::filesystem::path& out,
         const std::optional<std::filesystem::path>& path, std::optional<int> threads,
         const py::object& progress, const std::string& command_line) {
        if (threads && *threads < 0) throw InputError("", "threads", "must be >= 0 (0: all cores)");
        const JsonArgument config_file = json_argument(config, path, "prepare.json");
        PrepareOptions options;
        options.threads = threads.value_or(0);
        options.command_line = command_line;
        LongCall call(progress);
        options.progress = [&](const std::string& line) { call.report_line(line); };
        const PrepareReport report = call.run(
            [&] { return prepare_cloud(config_file.doc, config_file.file, out, options); });
        return report_dict(report);
      },
      py::arg("config"), py::arg("out"), py::arg("path"), py::arg("threads"), py::arg("progress"),
      py::arg("command_line"));
}

}  // namespace obscura::python
