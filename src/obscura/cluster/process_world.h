#pragma once
// The processes this run was started as. Launched by an MPI launcher (mpirun,
// mpiexec, srun: it sets OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK) in a
// build with MPI (OpenMPI, detected at configure time), MPI's world; else
// this process alone, without initialising MPI, so the same binary runs
// without a launcher. One per process, made first thing in main() and
// destroyed last (MPI_Init_thread / MPI_Finalize).
//
// Only the thread that made the world calls MPI (MPI_THREAD_FUNNELED): the
// library's collectives run on the calling thread, between parallel loops.
#include <memory>

#include "obscura/core/process_group.h"

namespace obscura {

class ProcessWorld {
 public:
  ProcessWorld(int& argc, char**& argv);
  ~ProcessWorld();
  ProcessWorld(const ProcessWorld&) = delete;
  ProcessWorld& operator=(const ProcessWorld&) = delete;

  const ProcessGroup& group() const;
  // More than one process.
  bool distributed() const { return group().size() > 1; }
  // Ends every process of the run with `status` (MPI_Abort), for a failure
  // that only this process met and could not share.
  [[noreturn]] void abort(int status) const;

  // Whether this build has MPI.
  static bool built_with_mpi();
  // Whether the environment says an MPI launcher started this process.
  static bool launched_by_mpi();

 private:
  struct Mpi;
  std::unique_ptr<Mpi> mpi_;  // null when alone
};

}  // namespace obscura
