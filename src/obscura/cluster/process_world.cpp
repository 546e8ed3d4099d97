#include "obscura/cluster/process_world.h"

#include <climits>
#include <cstdlib>
#include <numeric>

#include "obscura/core/check.h"
#include "obscura/core/error.h"

#ifdef OBSCURA_WITH_MPI
#include <mpi.h>
#endif

namespace obscura {

bool ProcessWorld::launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

#ifdef OBSCURA_WITH_MPI

namespace {

// MPI counts are ints: a message must stay under 2 GiB.
int message_count(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw Error("a message between processes of " + std::to_string(bytes) +
                " bytes exceeds MPI's 2 GiB limit: use fewer photons or smaller images per rank");
  return static_cast<int>(bytes);
}

void check_mpi(int code, const char* what) {
  OBSCURA_CHECK_MSG(code == MPI_SUCCESS, std::string(what) + " failed");
}

class MpiGroup final : public ProcessGroup {
 public:
  MpiGroup() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    int* tag_ub = nullptr;
    int found = 0;
    MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_TAG_UB, &tag_ub, &found);
    max_tag_ = found && tag_ub ? *tag_ub : 32767;  // the standard's guaranteed minimum
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::string> all_gather(const std::string& bytes) const override {
    int count = message_count(bytes.size());
    std::vector<int> counts(static_cast<std::size_t>(size_));
    check_mpi(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD),
              "MPI_Allgather");
    const std::vector<int> offsets = displacements(counts);
    std::string all(total(counts), '\0');
    check_mpi(MPI_Allgatherv(bytes.data(), count, MPI_BYTE, all.data(), counts.data(),
                             offsets.data(), MPI_BYTE, MPI_COMM_WORLD),
              "MPI_Allgatherv");
    return split(all, counts, offsets);
  }

  std::vector<std::string> gather(const std::string& bytes) const override {
    int count = message_count(bytes.size());
    std::vector<int> counts(static_cast<std::size_t>(size_));
    check_mpi(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD),
              "MPI_Gather");
    std::vector<int> offsets;
    std::string all;
    if (rank_ == 0) {
      offsets = displacements(counts);
      all.assign(total(counts), '\0');
    }
    check_mpi(MPI_Gatherv(bytes.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(),
                          MPI_BYTE, 0, MPI_COMM_WORLD),
              "MPI_Gatherv");
    if (rank_ != 0) return {};
    return split(all, counts, offsets);
  }

  std::string broadcast(const std::string& bytes) const override {
    int count = rank_ == 0 ? message_count(bytes.size()) : 0;
    check_mpi(MPI_Bcast(&count, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    std::string out = rank_ == 0 ? bytes : std::string(static_cast<std::size_t>(count), '\0');
    check_mpi(MPI_Bcast(out.data(), count, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    return out;
  }

  void send(int to, int tag, std::string bytes) const override {
    OBSCURA_CHECK(tag >= 0 && tag <= max_tag_);
    pending_.push_back({std::make_unique<std::string>(std::move(bytes)), MPI_REQUEST_NULL});
    Pending& p = pending_.back();
    check_mpi(MPI_Isend(p.bytes->data(), message_count(p.bytes->size()), MPI_BYTE, to, tag,
                        MPI_COMM_WORLD, &p.request),
              "MPI_Isend");
    // Completed sends free their buffers as others are queued.
    std::erase_if(pending_, [](Pending& q) {
      int done = 0;
      MPI_Test(&q.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }

  std::string receive(int tag) const override {
    MPI_Status status;
    check_mpi(MPI_Probe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &status), "MPI_Probe");
    return take(status);
  }

  std::optional<std::string> try_receive(int tag) const override {
    int arrived = 0;
    MPI_Status status;
    check_mpi(MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) return std::nullopt;
    return take(status);
  }

  std::unique_ptr<SharedCounter> make_counter() const override {
    // One 64-bit word on rank 0, none elsewhere; passive-target access.
    class Counter final : public SharedCounter {
     public:
      explicit Counter(int rank) {
        std::uint64_t* base = nullptr;
        check_mpi(MPI_Win_allocate(rank == 0 ? sizeof(std::uint64_t) : 0, sizeof(std::uint64_t),
                                   MPI_INFO_NULL, MPI_COMM_WORLD, &base, &window_),
                  "MPI_Win_allocate");
        if (rank == 0) *base = 0;
        MPI_Barrier(MPI_COMM_WORLD);  // the word is 0 before anyone draws
        check_mpi(MPI_Win_lock_all(MPI_MODE_NOCHECK, window_), "MPI_Win_lock_all");
      }
      ~Counter() override {
        MPI_Win_unlock_all(window_);
        MPI_Win_free(&window_);
      }
      std::uint64_t fetch_add(std::uint64_t n) override {
        std::uint64_t before = 0;
        check_mpi(MPI_Fetch_and_op(&n, &before, MPI_UINT64_T, 0, 0, MPI_SUM, window_),
                  "MPI_Fetch_and_op");
        check_mpi(MPI_Win_flush(0, window_), "MPI_Win_flush");
        return before;
      }

     private:
      MPI_Win window_ = MPI_WIN_NULL;
    };
    return std::make_unique<Counter>(rank_);
  }

  void finish_sends() const override {
    for (Pending& p : pending_) MPI_Wait(&p.request, MPI_STATUS_IGNORE);
    pending_.clear();
  }

 private:
  // Offsets of each rank's bytes in the gathered whole; the whole must itself
  // stay under MPI's int limit.
  static std::vector<int> displacements(const std::vector<int>& counts) {
    std::vector<int> offsets(counts.size());
    std::size_t at = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      offsets[r] = message_count(at);
      at += static_cast<std::size_t>(counts[r]);
    }
    message_count(at);
    return offsets;
  }
  static std::size_t total(const std::vector<int>& counts) {
    return std::accumulate(counts.begin(), counts.end(), std::size_t{0});
  }
  static std::vector<std::string> split(const std::string& all, const std::vector<int>& counts,
                                        const std::vector<int>& offsets) {
    std::vector<std::string> parts;
    for (std::size_t r = 0; r < counts.size(); ++r)
      parts.push_back(
          all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(counts[r])));
    return parts;
  }

  // The message `status` announced.
  std::string take(MPI_Status& status) const {
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::string bytes(static_cast<std::size_t>(count), '\0');
    check_mpi(MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG,
                       MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
    return bytes;
  }

  struct Pending {
    std::unique_ptr<std::string> bytes;  // stable while MPI reads it
    MPI_Request request;
  };

  int rank_ = 0, size_ = 1, max_tag_ = 32767;
  mutable std::vector<Pending> pending_;
};

}  // namespace

struct ProcessWorld::Mpi {
  MpiGroup group;
};

ProcessWorld::ProcessWorld(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  // Errors come back as codes (check_mpi) rather than ending the job unseen.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  mpi_ = std::make_unique<Mpi>();
}

ProcessWorld::~ProcessWorld() {
  if (mpi_) {
    mpi_.reset();
    MPI_Finalize();
  }
}

void ProcessWorld::abort(int status) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

bool ProcessWorld::built_with_mpi() { return true; }

const ProcessGroup& ProcessWorld::group() const {
  return mpi_ ? static_cast<const ProcessGroup&>(mpi_->group) : single_process();
}

#else  // without MPI: always this process alone

struct ProcessWorld::Mpi {};

ProcessWorld::ProcessWorld(int& /*argc*/, char**& /*argv*/) {
  // N copies of the whole job writing the same files would be worse than none.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* size = std::getenv(name); size && std::atoi(size) > 1)
      throw Error(std::string("started by an MPI launcher as ") + size +
                  " processes, but this obscura was built without MPI (scripts/install-deps "
                  "installs libopenmpi-dev; then reconfigure): run it without mpirun");
}
ProcessWorld::~ProcessWorld() = default;
void ProcessWorld::abort(int status) const { std::exit(status); }
bool ProcessWorld::built_with_mpi() { return false; }
const ProcessGroup& ProcessWorld::group() const { return single_process(); }

#endif

}  // namespace obscura
