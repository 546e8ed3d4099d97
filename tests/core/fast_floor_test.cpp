// fast_floor (core/fast_floor.h) against std::floor, bit for bit.
#include "obscura/core/fast_floor.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "obscura/core/rng.h"

namespace obscura {
namespace {

void expect_floor_bits(double x) {
  const double expected = std::floor(x), got = fast_floor(x);
  if (std::isnan(expected)) {
    EXPECT_TRUE(std::isnan(got)) << x;
    return;
  }
  EXPECT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(expected))
      << x << ": " << got << " instead of " << expected;
}

// The edges: zeros of both signs, whole numbers and their neighbours either
// side, the halves, 2^52 and 2^63 where truncation to an integer stops
// being possible, infinities, NaN and subnormals.
TEST(FastFloor, EqualsStdFloorAtTheEdges) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> xs = {0.0,
                            -0.0,
                            0.5,
                            -0.5,
                            inf,
                            -inf,
                            std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::denorm_min(),
                            -std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max()};
  for (const double whole :
       {1.0, 2.0, 3.0, 1e6, 2147483647.0, 2147483648.0, 4503599627370495.0, 4503599627370496.0,
        9007199254740992.0, 9223372036854775808.0, 1e300}) {
    for (const double s : {1.0, -1.0}) {
      const double w = s * whole;
      xs.insert(xs.end(), {w, std::nextafter(w, inf), std::nextafter(w, -inf), w + 0.5 * s});
    }
  }
  for (const double x : xs) expect_floor_bits(x);
}

// Random doubles over many magnitudes, both signs.
TEST(FastFloor, EqualsStdFloorAtRandomPoints) {
  Rng rng(17, 0);
  for (int i = 0; i < 200000; ++i) {
    const double magnitude = std::ldexp(1.0, static_cast<int>(rng.uniform() * 140) - 70);
    expect_floor_bits((rng.uniform() - 0.5) * 2.0 * magnitude);
  }
}

}  // namespace
}  // namespace obscura
