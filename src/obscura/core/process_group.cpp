#include "obscura/core/process_group.h"

#include <fmt/format.h>

#include <atomic>
#include <new>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"

namespace obscura {
namespace {

class SingleProcess final : public ProcessGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::vector<std::string> all_gather(const std::string& bytes) const override { return {bytes}; }
  std::vector<std::string> gather(const std::string& bytes) const override { return {bytes}; }
  std::string broadcast(const std::string& bytes) const override { return bytes; }
  // Alone, there is nobody to send to.
  void send(int, int, std::string) const override {
    OBSCURA_CHECK_MSG(false, "a message to another process in a run of one process");
  }
  std::string receive(int) const override {
    OBSCURA_CHECK_MSG(false, "waiting for a message in a run of one process");
    return {};
  }
  std::optional<std::string> try_receive(int) const override { return std::nullopt; }
  void finish_sends() const override {}
  std::unique_ptr<SharedCounter> make_counter() const override {
    struct Counter final : SharedCounter {
      std::uint64_t value = 0;
      std::uint64_t fetch_add(std::uint64_t n) override {
        const std::uint64_t before = value;
        value += n;
        return before;
      }
    };
    return std::make_unique<Counter>();
  }
};

// How a failure travels: its kind, and what is needed to make the same error
// again on rank 0 (an InputError keeps its file and field).
enum class FailureKind : std::uint8_t { kError, kInput, kInternal, kPeer };

std::atomic<bool> shared_failure_seen{false};

}  // namespace

bool failure_was_shared() { return shared_failure_seen; }

std::string encode_failure(const std::exception_ptr& failure) {
  if (!failure) return {};
  ByteWriter w;
  try {
    std::rethrow_exception(failure);
  } catch (const PeerFailure& e) {
    w.put(FailureKind::kPeer);
    w.put<std::uint8_t>(e.internal() ? 1 : 0);
    w.put_string(e.what());
  } catch (const InputError& e) {
    w.put(FailureKind::kInput);
    w.put_string(e.file());
    w.put_string(e.field());
    w.put_string(e.detail());
  } catch (const InternalError& e) {
    w.put(FailureKind::kInternal);
    w.put_string(e.what());
  } catch (const Error& e) {
    w.put(FailureKind::kError);
    w.put_string(e.what());
  } catch (const std::bad_alloc&) {
    w.put(FailureKind::kInternal);
    w.put_string("out of memory in an allocation that was not checked first");
  } catch (const std::exception& e) {
    w.put(FailureKind::kInternal);
    w.put_string(e.what());
  } catch (...) {
    w.put(FailureKind::kInternal);
    w.put_string("unknown exception");
  }
  return w.take();
}

std::exception_ptr decode_failure(const std::string& bytes, int from_rank) {
  if (bytes.empty()) return nullptr;
  ByteReader in(bytes);
  const auto kind = in.get<FailureKind>();
  const std::string where = from_rank == 0 ? "" : fmt::format("rank {}: ", from_rank);
  switch (kind) {
    case FailureKind::kInput: {
      std::string file = in.get_string(), field = in.get_string(), detail = in.get_string();
      if (!where.empty()) detail += " (on " + where.substr(0, where.size() - 2) + ")";
      return std::make_exception_ptr(InputError(std::move(file), std::move(field), detail));
    }
    case FailureKind::kInternal:
      return std::make_exception_ptr(InternalError(where + in.get_string()));
    case FailureKind::kPeer: {
      const bool internal = in.get<std::uint8_t>() != 0;
      return std::make_exception_ptr(PeerFailure(in.get_string(), internal));
    }
    default:
      return std::make_exception_ptr(Error(where + in.get_string()));
  }
}

const ProcessGroup& single_process() {
  static const SingleProcess group;
  return group;
}

void share_failure(const ProcessGroup& group, const std::exception_ptr& failure) {
  if (group.size() == 1) {
    if (failure) std::rethrow_exception(failure);
    return;
  }
  const std::vector<std::string> all = group.all_gather(encode_failure(failure));
  for (const std::string& bytes : all)
    if (!bytes.empty()) shared_failure_seen = true;
  for (int r = 0; r < static_cast<int>(all.size()); ++r) {
    const std::string& bytes = all[static_cast<std::size_t>(r)];
    if (bytes.empty()) continue;
    if (!group.is_root()) {
      bool internal = false;
      try {
        std::rethrow_exception(decode_failure(bytes, r));
      } catch (const InternalError&) {
        internal = true;
      } catch (const PeerFailure& e) {
        internal = e.internal();
      } catch (...) {
      }
      throw PeerFailure(fmt::format("rank {} failed", r), internal);
    }
    std::rethrow_exception(r == 0 ? failure : decode_failure(bytes, r));
  }
}

}  // namespace obscura
