#pragma once
// The processes one run is shared among: the ranks of an MPI job
// (cluster/process_world.h) or this process alone. The library shares work
// through this interface and never names MPI, so every layer builds and runs
// without it. Collectives move bytes (core/byte_stream.h packs them) and must
// be called by every process of the group, in the same order, from the thread
// that made the group.
//
// Failures: run_together() turns an error on any process into an error on
// all of them at the same point, so that rank 0 can report it once and every
// process can end cleanly (a process that failed alone inside other
// collectives would leave the rest waiting).
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "obscura/core/error.h"

namespace obscura {

// A counter every process of a group draws from, for handing out work to
// whichever process is free (MPI: an atomic fetch-and-add on rank 0's memory
// that needs no call from rank 0, MPI_Fetch_and_op).
class SharedCounter {
 public:
  virtual ~SharedCounter() = default;
  // The counter's value before adding `n` (it starts at 0).
  virtual std::uint64_t fetch_add(std::uint64_t n) = 0;
};

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool is_root() const { return rank() == 0; }

  // Every process's `bytes`, in rank order, on every process.
  virtual std::vector<std::string> all_gather(const std::string& bytes) const = 0;
  // Every process's `bytes`, in rank order, on rank 0; empty on the others.
  virtual std::vector<std::string> gather(const std::string& bytes) const = 0;
  // Rank 0's `bytes` on every process (`bytes` is ignored elsewhere).
  virtual std::string broadcast(const std::string& bytes) const = 0;

  // Point to point, for work handed over as it completes rather than in
  // lockstep. send() returns at once and keeps the bytes until they are
  // delivered; every message sent must be received, and finish_sends() waits
  // until this process's messages are. `tag` >= 0 names the message: one
  // message per tag and destination.
  virtual void send(int to, int tag, std::string bytes) const = 0;
  // The message sent to this process under `tag` by any process: waits for it.
  virtual std::string receive(int tag) const = 0;
  // The same if it has arrived, else nullopt.
  virtual std::optional<std::string> try_receive(int tag) const = 0;
  virtual void finish_sends() const = 0;

  // A new counter at 0. Collective: every process makes it, and destroys it,
  // together (MPI_Win_allocate / MPI_Win_free).
  virtual std::unique_ptr<SharedCounter> make_counter() const = 0;
};

// This process alone: rank 0 of 1, collectives that return their input.
const ProcessGroup& single_process();

// Thrown on the processes other than rank 0 when a failure is shared
// (run_together, share_failure): rank 0 reports it, the others end quietly
// with the same exit status. `internal`: the failure was a bug (exit 2),
// else bad input or a failed run (exit 1).
class PeerFailure : public Error {
 public:
  PeerFailure(const std::string& what, bool internal) : Error(what), internal_(internal) {}
  bool internal() const { return internal_; }

 private:
  bool internal_;
};

// A failure as bytes for another process ("" for none), and back: the same
// kind of error (InputError with its file and field, InternalError, Error)
// with the same message, the rank it came from added when that is not 0.
// Null for "".
std::string encode_failure(const std::exception_ptr& failure);
std::exception_ptr decode_failure(const std::string& bytes, int from_rank);

// Tells every process whether any of them failed (`failure` null where it did
// not). When one did, every process throws: rank 0 the failure of the lowest
// failing rank (its own exception when it failed itself, else the same kind
// of error with the same message, prefixed by the rank when that is not 0),
// the others a PeerFailure. Returns normally only when none failed.
void share_failure(const ProcessGroup& group, const std::exception_ptr& failure);

// Whether share_failure has thrown on this process: every process knows of a
// failure and is ending, so none waits in a collective (the tool ends the
// others itself, MPI_Abort, after any failure that was not shared).
bool failure_was_shared();

// Runs `work` on every process and shares its failure (share_failure).
template <class Work>
void run_together(const ProcessGroup& group, Work&& work) {
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  share_failure(group, failure);
}

}  // namespace obscura
