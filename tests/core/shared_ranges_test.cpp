// Work shared by ranges (core/shared_ranges.h): each of 1, 2 and 3 processes
// (threads standing in for MPI ranks) fills only its own ranges, of uneven
// lengths and order; afterwards every process holds the whole array, bit
// for bit, and values outside every range stay as they were.
#include "obscura/core/shared_ranges.h"

#include <gtest/gtest.h>

#include <vector>

#include "support/thread_process_group.h"

namespace obscura {
namespace {

double value_at(std::size_t i) { return 0.5 + 1e-3 * static_cast<double>(i * i); }

TEST(SharedRanges, EveryProcessEndsWithEveryProcesssRanges) {
  // Ranges of process r: every third run of 7 values starting at 7r, the
  // last one shortened; index 0…2 belong to nobody.
  const std::size_t size = 100;
  const auto ranges_of = [&](int ranks, int r) {
    IndexRanges ranges;
    for (std::size_t begin = 3 + 7 * static_cast<std::size_t>(r); begin < size;
         begin += 7 * static_cast<std::size_t>(ranks))
      ranges.emplace_back(begin, std::min(begin + 7, size));
    return ranges;
  };
  for (const int ranks : {1, 2, 3}) {
    std::vector<std::vector<double>> held(static_cast<std::size_t>(ranks));
    testing::run_ranks(ranks, [&](const ProcessGroup& processes) {
      std::vector<double> data(size, -1.0);
      for (const auto& [begin, end] : ranges_of(ranks, processes.rank()))
        for (std::size_t i = begin; i < end; ++i) data[i] = value_at(i);
      share_ranges(processes, data, [&](int r) { return ranges_of(ranks, r); });
      held[static_cast<std::size_t>(processes.rank())] = data;
    });
    for (int r = 0; r < ranks; ++r) {
      const std::vector<double>& data = held[static_cast<std::size_t>(r)];
      for (std::size_t i = 0; i < size; ++i)
        EXPECT_EQ(data[i], i < 3 ? -1.0 : value_at(i))
            << ranks << " ranks, rank " << r << ", " << i;
    }
  }
}

}  // namespace
}  // namespace obscura
