#pragma once
// Work shared among processes by ranges of one array (core/process_group.h):
// every process holds the whole array but computes only its own ranges, then
// share_ranges sends each process the others' values, so that all hold the
// bits one process would have made alone (the radiance cache's sun depths,
// kernel integrals and splatted slabs under MPI).
#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/core/process_group.h"

namespace obscura {

// Index ranges [first, second) of an array.
using IndexRanges = std::vector<std::pair<std::size_t, std::size_t>>;

// Collective. `ranges_of(r)` gives the IndexRanges process r computed, the
// same on every process; ranges of different processes do not overlap.
template <class T, class RangesOf>
void share_ranges(const ProcessGroup& processes, std::vector<T>& data, RangesOf&& ranges_of) {
  const int ranks = processes.size(), rank = processes.rank();
  if (ranks == 1) return;
  std::vector<T> mine;
  for (const auto& [begin, end] : ranges_of(rank))
    mine.insert(mine.end(), data.begin() + begin, data.begin() + end);
  ByteWriter out;
  out.put_vector(mine);
  const std::vector<std::string> all = processes.all_gather(out.take());
  for (int r = 0; r < ranks; ++r) {
    if (r == rank) continue;
    ByteReader in(all[static_cast<std::size_t>(r)]);
    const std::vector<T> theirs = in.get_vector<T>();
    std::size_t at = 0;
    for (const auto& [begin, end] : ranges_of(r)) {
      OBSCURA_CHECK(at + (end - begin) <= theirs.size());
      std::copy(theirs.begin() + at, theirs.begin() + at + (end - begin), data.begin() + begin);
      at += end - begin;
    }
    OBSCURA_CHECK(at == theirs.size());
  }
}

}  // namespace obscura
