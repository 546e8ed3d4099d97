#include "long_call.h"

namespace obscura::python {

LongCall::LongCall(py::object progress, const Scene& scene)
    : progress_(std::move(progress)), scene_(&scene) {}

LongCall::LongCall(py::object progress) : progress_(std::move(progress)) {}

void LongCall::report(const RenderProgress& p) {
  forward([&] {
    py::dict d;
    d["frame"] = p.frame;
    d["frames"] = p.frames;
    d["time_s"] = p.time_s;
    if (p.sensor < 0) {  // the frame's photons, before its sensors
      d["sensor"] = py::none();
      d["photons_done"] = p.photons_done;
      d["photons_total"] = p.photons_total;
    } else {
      d["sensor"] = scene_->sensors.at(static_cast<std::size_t>(p.sensor)).name;
      d["rows_done"] = p.rows_done;
      d["rows_total"] = p.rows_total;
    }
    return py::object(d);
  });
}

void LongCall::report_line(const std::string& line) {
  forward([&] { return py::object(py::str(line)); });
}

void LongCall::forward(const std::function<py::object()>& arg) {
  if (stopping_) throw Stopped{};
  std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) throw Stopped{};
  py::gil_scoped_acquire gil;
  try {
    // Signals are handled only on Python's main thread; elsewhere this is a
    // no-op, and the main thread reports too (it takes part in the loop).
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!progress_.is_none()) progress_(arg());
  } catch (...) {
    stopped_ = std::current_exception();
    stopping_ = true;
    throw Stopped{};
  }
}

}  // namespace obscura::python
