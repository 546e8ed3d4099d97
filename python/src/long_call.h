#pragma once
// A long library call (a render, a preparation, a study) run from Python: the
// GIL is released for its duration, so other Python threads run; progress
// reports are forwarded to an optional Python callable, and at each report
// Ctrl-C is checked
// (PyErr_CheckSignals), so a render stops at the next image row with
// KeyboardInterrupt instead of running to its end. An exception raised by the
// callable stops the render the same way and reaches the caller unchanged.
#include <pybind11/pybind11.h>

#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "obscura/sequence/sequence_runner.h"

namespace obscura::python {

namespace py = pybind11;

class LongCall {
 public:
  // `progress`: None or a callable taking one dict (frame, frames, time_s,
  // sensor, rows_done, rows_total; or, while a frame's photons are traced,
  // sensor None, photons_done, photons_total) per render report of `scene`.
  LongCall(py::object progress, const Scene& scene);
  // `progress`: None or a callable taking one line of text per report.
  explicit LongCall(py::object progress);

  // What the library's progress callbacks call, from any thread. Throws (a
  // type the library does not catch) to stop the call once Ctrl-C was
  // pressed or the callable raised.
  void report(const RenderProgress& p);
  void report_line(const std::string& line);

  // Runs f() without the GIL; rethrows what stopped it (KeyboardInterrupt,
  // the callable's exception) or the library's own error.
  template <typename F>
  auto run(F&& f) -> decltype(f()) {
    std::optional<decltype(f())> result;
    {
      py::gil_scoped_release release;
      try {
        result.emplace(f());
      } catch (const Stopped&) {
        // stopped_ holds why; rethrown below with the GIL held.
      }
    }
    if (stopped_) std::rethrow_exception(stopped_);
    return std::move(*result);
  }

 private:
  struct Stopped {};  // not a std::exception: nothing in the library catches it
  // Checks Ctrl-C and calls the callable with arg() (made with the GIL held).
  void forward(const std::function<py::object()>& arg);
  py::object progress_;
  const Scene* scene_ = nullptr;  // render reports only
  std::mutex mutex_;              // one Python call at a time, reports in order
  std::atomic<bool> stopping_{false};
  std::exception_ptr stopped_;
};

}  // namespace obscura::python
