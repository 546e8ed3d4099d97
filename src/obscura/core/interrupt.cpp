#include "obscura/core/interrupt.h"

#include <atomic>
#include <csignal>
#include <string>

namespace obscura {
namespace {

std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

extern "C" void on_signal(int signal) {
  if (received.exchange(signal) == signal) {
    // The second of its kind: the user insists. Default action, at once.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

std::string describe(int signal) {
  return signal == SIGINT    ? "interrupted (SIGINT)"
         : signal == SIGTERM ? "terminated (SIGTERM)"
                             : "stopped by signal " + std::to_string(signal);
}

}  // namespace

Interrupted::Interrupted(int signal, const std::string& detail)
    : Error(describe(signal) + detail), signal_(signal) {}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return received.load(); }

void throw_if_interrupted() {
  if (const int s = received.load()) throw Interrupted(s);
}

}  // namespace obscura
