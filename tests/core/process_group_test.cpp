// What the processes of a run share (core/process_group.h): messages packed
// and read back, failures carried between ranks with their kind and message,
// and a failure on one rank ending every rank at the same point.
#include "obscura/core/process_group.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "support/thread_process_group.h"

namespace obscura {
namespace {

TEST(ByteStream, ValuesStringsAndVectorsReadBackInOrder) {
  ByteWriter w;
  w.put(3.25);
  w.put_string("lwir");
  w.put_vector(std::vector<float>{1.5f, -2.0f});
  w.put(std::array<double, 3>{1, 2, 3});
  const std::string bytes = w.take();
  ByteReader r(bytes);
  EXPECT_EQ(r.get<double>(), 3.25);
  EXPECT_EQ(r.get_string(), "lwir");
  EXPECT_EQ(r.get_vector<float>(), (std::vector<float>{1.5f, -2.0f}));
  EXPECT_EQ((r.get<std::array<double, 3>>()), (std::array<double, 3>{1, 2, 3}));
  EXPECT_TRUE(r.done());
}

TEST(ByteStream, ReadingPastTheEndIsAnInternalError) {
  ByteWriter w;
  w.put<std::uint64_t>(1000);  // a vector length with no values behind it
  const std::string bytes = w.take();
  ByteReader r(bytes);
  EXPECT_THROW(r.get_vector<double>(), InternalError);
  ByteReader short_read(std::string("ab"));
  EXPECT_THROW(short_read.get<double>(), InternalError);
}

TEST(ProcessGroup, TheSingleProcessIsRankZeroOfOne) {
  const ProcessGroup& g = single_process();
  EXPECT_EQ(g.rank(), 0);
  EXPECT_EQ(g.size(), 1);
  EXPECT_EQ(g.all_gather("x"), std::vector<std::string>{"x"});
  EXPECT_EQ(g.gather("y"), std::vector<std::string>{"y"});
  EXPECT_EQ(g.broadcast("z"), "z");
  EXPECT_THROW(run_together(g, [] { throw Error("boom"); }), Error);
}

TEST(ProcessGroup, FailuresTravelWithTheirKindFileAndField) {
  const std::string input =
      encode_failure(std::make_exception_ptr(InputError("scene.json", "/sensors/0", "bad")));
  try {
    std::rethrow_exception(decode_failure(input, 2));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.field(), "/sensors/0");
    EXPECT_EQ(e.detail(), "bad (on rank 2)");
  }
  const std::string internal = encode_failure(std::make_exception_ptr(InternalError("bug")));
  EXPECT_THROW(std::rethrow_exception(decode_failure(internal, 0)), InternalError);
  EXPECT_EQ(decode_failure("", 1), nullptr);
  EXPECT_EQ(encode_failure(nullptr), "");
}

TEST(ProcessGroup, ThreadRanksGatherInRankOrder) {
  testing::run_ranks(3, [](const ProcessGroup& g) {
    const std::vector<std::string> all = g.all_gather(std::to_string(g.rank()));
    EXPECT_EQ(all, (std::vector<std::string>{"0", "1", "2"}));
    const std::vector<std::string> root = g.gather("r" + std::to_string(g.rank()));
    EXPECT_EQ(root.size(), g.is_root() ? 3u : 0u);
    EXPECT_EQ(g.broadcast(g.is_root() ? "from 0" : "ignored"), "from 0");
  });
}

TEST(ProcessGroup, AFailureOnOneRankEndsEveryRankAndRankZeroReportsIt) {
  std::atomic<int> peers{0}, root_saw_input_error{0};
  testing::run_ranks(3, [&](const ProcessGroup& g) {
    try {
      run_together(g, [&] {
        if (g.rank() == 2) throw InputError("k3.vdb", "sigma_a", "truncated");
      });
      ADD_FAILURE() << "rank " << g.rank() << " went on after a failure";
    } catch (const PeerFailure& e) {
      EXPECT_NE(g.rank(), 0);
      EXPECT_FALSE(e.internal());
      ++peers;
    } catch (const InputError& e) {
      EXPECT_EQ(g.rank(), 0);
      EXPECT_EQ(e.file(), "k3.vdb");
      EXPECT_NE(std::string(e.what()).find("rank 2"), std::string::npos) << e.what();
      ++root_saw_input_error;
    }
  });
  EXPECT_EQ(peers, 2);
  EXPECT_EQ(root_saw_input_error, 1);
  EXPECT_TRUE(failure_was_shared());
}

TEST(ProcessGroup, NoFailureMeansEveryRankGoesOn) {
  std::atomic<int> went_on{0};
  testing::run_ranks(2, [&](const ProcessGroup& g) {
    run_together(g, [] {});
    ++went_on;
  });
  EXPECT_EQ(went_on, 2);
}

}  // namespace
}  // namespace obscura
