#pragma once
// Stopping a long run cleanly on SIGINT (Ctrl-C) or SIGTERM (a batch system's
// "time is up"): the handler only records the signal; long loops call
// throw_if_interrupted() where stopping is safe (between image rows,
// keyframes, frames, study cases), and the exception unwinds through the
// usual paths, so temporaries are removed (io/atomic_file.h), completed
// frames are kept and recorded, and the tool exits 128 + the signal's number
// (130, 143). A second signal of the same kind ends the process at once, for
// a run that does not reach a check soon enough.
#include <string>

#include "obscura/core/error.h"

namespace obscura {

// Thrown where a run stops after SIGINT or SIGTERM.
class Interrupted : public Error {
 public:
  // `detail` follows the signal's description (what was kept, say).
  explicit Interrupted(int signal, const std::string& detail = "");
  int signal() const { return signal_; }

 private:
  int signal_;
};

// Installs the handlers for SIGINT and SIGTERM (the tool does, once).
void install_interrupt_handlers();
// The signal received since the handlers were installed, else 0.
int interrupt_signal();
// Throws Interrupted once a signal was received.
void throw_if_interrupted();

}  // namespace obscura
