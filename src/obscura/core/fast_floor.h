#pragma once
// std::floor without a library call. The project builds for plain x86-64,
// which has no rounding instruction before SSE4.1, so std::floor is a call
// into libm (about 19 instructions; a third of the radiance cache's
// lattice lookups in a slab validation, docs/performance.md).
#include <cmath>
#include <cstdint>

#include "obscura/core/host_device.h"

namespace obscura {

// Exactly std::floor(x) for every double: the truncation towards zero, one
// less where that rounded up (x negative and not whole). Whole numbers
// (−0.0 included) and NaN come back as they are, and beyond 2^52 every
// double is whole.
OBSCURA_HOST_DEVICE inline double fast_floor(double x) {
  constexpr double kAllWhole = 4503599627370496.0;  // 2^52
  if (!(x > -kAllWhole && x < kAllWhole)) return x;
  const double t = static_cast<double>(static_cast<std::int64_t>(x));
  if (t == x) return x;
  return t > x ? t - 1.0 : t;
}

}  // namespace obscura
