#include "obscura/render/radiance_cache/kernel_sums.h"

#include <algorithm>

#include "obscura/core/check.h"
#include "obscura/core/parallel.h"

namespace obscura {
namespace {

// Arrays over the lattice's box, x fastest.
struct Box {
  std::array<int, 3> n;
  std::size_t count() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  std::size_t stride(int axis) const {
    return axis == 0   ? 1
           : axis == 1 ? static_cast<std::size_t>(n[0])
                       : static_cast<std::size_t>(n[0]) * n[1];
  }
};

// out(n) = Σ_d f(n_a, d) in(n + d e_a) along axis a, f = `factor` (2r + 1
// values per node index along a), over the neighbours inside the box, for
// every node; the lines along a in parallel.
void pass(const Box& box, int axis, int r, const std::vector<double>& factor,
          const std::vector<double>& in, std::vector<double>& out, int threads) {
  const int other[2] = {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2};
  const int length = box.n[axis];
  const std::size_t step = box.stride(axis);
  const std::size_t lines = static_cast<std::size_t>(box.n[other[0]]) * box.n[other[1]];
  const std::size_t span = 2 * static_cast<std::size_t>(r) + 1;
  parallel_for(lines, threads, [&](std::size_t line) {
    const auto u = static_cast<int>(line % box.n[other[0]]),
               v = static_cast<int>(line / box.n[other[0]]);
    const std::size_t first = u * box.stride(other[0]) + v * box.stride(other[1]);
    for (int i = 0; i < length; ++i) {
      const double* f = factor.data() + static_cast<std::size_t>(i) * span;
      double sum = 0.0;
      for (int d = std::max(-r, -i); d <= std::min(r, length - 1 - i); ++d)
        sum += f[d + r] * in[first + static_cast<std::size_t>(i + d) * step];
      out[first + static_cast<std::size_t>(i) * step] = sum;
    }
  });
}

}  // namespace

bool kernel_sums_fit(const NodeLattice& lattice) {
  const std::array<int, 3>& n = lattice.dims();
  return !lattice.periodic() &&
         static_cast<double>(n[0]) * n[1] * n[2] <= 2.0 * static_cast<double>(lattice.slot_count());
}

void kernel_sums(const NodeLattice& lattice, int r, const std::array<AxisOverlaps, 3>& overlaps,
                 const std::vector<float>& sigma_s, int samples, int threads,
                 std::vector<float>& out) {
  OBSCURA_CHECK(kernel_sums_fit(lattice));
  const Box box{lattice.dims()};
  const std::size_t count = box.count();
  // Each box node's slot (none where its block is not held).
  std::vector<std::size_t> slot(count);
  parallel_for(static_cast<std::size_t>(box.n[2]), threads, [&](std::size_t z) {
    for (int y = 0; y < box.n[1]; ++y)
      for (int x = 0; x < box.n[0]; ++x)
        slot[x + box.stride(1) * y + box.stride(2) * z] =
            lattice.slot_of(x, y, static_cast<int>(z));
  });
  std::vector<double> values(count), x0(count), x1(count), y00(count), y01(count), y10(count);
  constexpr int kMoments = 4;
  for (int k = 0; k < samples; ++k) {
    for (std::size_t i = 0; i < count; ++i)
      values[i] = slot[i] == NodeLattice::kNoSlot
                      ? 0.0
                      : sigma_s[slot[i] * static_cast<std::size_t>(samples) + k];
    pass(box, 0, r, overlaps[0].weight, values, x0, threads);
    pass(box, 0, r, overlaps[0].moment, values, x1, threads);
    pass(box, 1, r, overlaps[1].weight, x0, y00, threads);
    pass(box, 1, r, overlaps[1].moment, x0, y01, threads);
    pass(box, 1, r, overlaps[1].weight, x1, y10, threads);
    // The z passes' outputs S0, Sx, Sy, Sz into arrays whose inputs are spent.
    pass(box, 2, r, overlaps[2].weight, y00, values, threads);
    pass(box, 2, r, overlaps[2].weight, y10, x0, threads);
    pass(box, 2, r, overlaps[2].weight, y01, x1, threads);
    pass(box, 2, r, overlaps[2].moment, y00, y10, threads);
    const std::vector<double>* sums[kMoments] = {&values, &x0, &x1, &y10};
    parallel_for(count, threads, [&](std::size_t i) {
      if (slot[i] == NodeLattice::kNoSlot) return;
      float* o = out.data() + (slot[i] * static_cast<std::size_t>(samples) + k) * kMoments;
      for (int q = 0; q < kMoments; ++q) o[q] = static_cast<float>((*sums[q])[i]);
    });
  }
}

}  // namespace obscura
