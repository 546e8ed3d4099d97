#pragma once
// Parallel loops over independent work items with a chosen number of threads.
// Work items never share random state (each owns its Rng stream), so results do
// not depend on the thread count or on scheduling.
#include <cstddef>
#include <functional>

namespace obscura {

// Runs body(i) for i in [0, count) on `threads` threads (0: all cores).
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

// Number of threads `threads` resolves to (0 means all cores).
int resolve_thread_count(int threads);

}  // namespace obscura
