#pragma once
// A group of N "processes" that are threads of the test, for testing what the
// library shares among MPI ranks (core/process_group.h) without MPI: run_ranks
// starts one thread per rank, each with its own group object, and the
// collectives meet at a barrier. The same code paths run as under mpirun;
// only the transport differs (cluster/process_world.cpp is tested by the
// mpirun CLI tests).
#include <atomic>
#include <barrier>
#include <condition_variable>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "obscura/core/process_group.h"

namespace obscura::testing {

class ThreadProcessGroup final : public ProcessGroup {
 public:
  struct Shared {
    explicit Shared(int n) : size(n), slots(static_cast<std::size_t>(n)), sync(n) {}
    int size;
    std::vector<std::string> slots;
    std::barrier<> sync;
    // Point-to-point messages: (destination, tag) → bytes.
    std::mutex mail_mutex;
    std::condition_variable mail_arrived;
    std::map<std::pair<int, int>, std::string> mail;
    std::atomic<std::uint64_t> counter{0};
  };

  ThreadProcessGroup(std::shared_ptr<Shared> shared, int rank)
      : shared_(std::move(shared)), rank_(rank) {}

  int rank() const override { return rank_; }
  int size() const override { return shared_->size; }

  std::vector<std::string> all_gather(const std::string& bytes) const override {
    shared_->slots[static_cast<std::size_t>(rank_)] = bytes;
    shared_->sync.arrive_and_wait();
    std::vector<std::string> all = shared_->slots;
    shared_->sync.arrive_and_wait();  // nobody writes a slot before all have read
    return all;
  }
  std::vector<std::string> gather(const std::string& bytes) const override {
    std::vector<std::string> all = all_gather(bytes);
    return rank_ == 0 ? all : std::vector<std::string>{};
  }
  std::string broadcast(const std::string& bytes) const override {
    return all_gather(rank_ == 0 ? bytes : std::string()).front();
  }
  void send(int to, int tag, std::string bytes) const override {
    std::lock_guard lock(shared_->mail_mutex);
    shared_->mail[{to, tag}] = std::move(bytes);
    shared_->mail_arrived.notify_all();
  }
  std::string receive(int tag) const override {
    std::unique_lock lock(shared_->mail_mutex);
    shared_->mail_arrived.wait(lock, [&] { return shared_->mail.count({rank_, tag}) > 0; });
    return take(tag);
  }
  std::optional<std::string> try_receive(int tag) const override {
    std::lock_guard lock(shared_->mail_mutex);
    if (!shared_->mail.count({rank_, tag})) return std::nullopt;
    return take(tag);
  }
  void finish_sends() const override {}  // delivered when sent
  std::unique_ptr<SharedCounter> make_counter() const override {
    struct Counter final : SharedCounter {
      std::atomic<std::uint64_t>* value;
      explicit Counter(std::atomic<std::uint64_t>* v) : value(v) {}
      std::uint64_t fetch_add(std::uint64_t n) override { return value->fetch_add(n); }
    };
    // Nobody draws from the last counter once everyone is here; then rank 0
    // starts the new one at 0 before anybody draws from it.
    shared_->sync.arrive_and_wait();
    if (rank_ == 0) shared_->counter = 0;
    shared_->sync.arrive_and_wait();
    return std::make_unique<Counter>(&shared_->counter);
  }

 private:
  std::string take(int tag) const {  // with mail_mutex held
    const auto it = shared_->mail.find({rank_, tag});
    std::string bytes = std::move(it->second);
    shared_->mail.erase(it);
    return bytes;
  }

  std::shared_ptr<Shared> shared_;
  int rank_;
};

// Runs work(group) on `ranks` threads, one rank each; rethrows the first
// exception a rank ended with, after all have ended.
inline void run_ranks(int ranks, const std::function<void(const ProcessGroup&)>& work) {
  auto shared = std::make_shared<ThreadProcessGroup::Shared>(ranks);
  std::vector<std::exception_ptr> failures(static_cast<std::size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      const ThreadProcessGroup group(shared, r);
      try {
        work(group);
      } catch (...) {
        failures[static_cast<std::size_t>(r)] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& f : failures)
    if (f) std::rethrow_exception(f);
}

}  // namespace obscura::testing
