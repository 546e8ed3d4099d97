#pragma once
// e^x to within a few ulp, inline and without libm's call and error
// handling: what the cell quadrature (render/emission_absorption/
// cell_quadrature.h) evaluates twice per cell and spectral node, where the
// libm call cost as much as the rest of the cell (callgrind, docs/performance.md).
// Cody–Waite range reduction x = k ln 2 + r, |r| ≤ ½ ln 2 (ln 2 split in two
// so that k ln 2 is exact), then e^r by its Taylor series to degree 12, whose
// remainder |r|¹³/13! ≤ 1.7e-16 is below double rounding, and 2^k built in
// the exponent bits. Results below 2^−1022 (x < −708.39) are returned as 0
// (an absolute error below 2.3e-308); above x = 700, where 2^k would
// overflow before the product, libm's exp answers; NaN stays NaN. The same
// code on a CUDA device (core/host_device.h), where exp is CUDA's.
#include <bit>
#include <cmath>
#include <cstdint>

#include "obscura/core/host_device.h"

namespace obscura {

OBSCURA_HOST_DEVICE inline double fast_exp(double x) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // high bits of ln 2 (exact k ln2_hi)
  constexpr double kLn2Lo = 1.90821492927058770002e-10;  // ln 2 − kLn2Hi
  constexpr double kRound = 6755399441055744.0;  // 1.5 · 2^52: adding it rounds to an integer
  if (!(x > -708.39)) return x != x ? x : 0.0;
  if (x > 700.0) return std::exp(x);
  const double k = (x * kLog2e + kRound) - kRound;
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double p = 1.0 / 479001600.0;  // 1/12!
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  const auto bits = static_cast<std::uint64_t>(static_cast<std::int64_t>(k) + 1023) << 52;
  return p * std::bit_cast<double>(bits);
}

// e^{−x} for 0 ≤ x ≤ 0.1 (the cell quadrature's thin cells): its Taylor
// series to degree 9, whose remainder x¹⁰/10! ≤ 2.8e-17 is below rounding.
OBSCURA_HOST_DEVICE inline double exp_neg_small(double x) {
  // Estrin's scheme: the same polynomial in four levels of independent
  // multiply-adds instead of Horner's chain of nine, whose latency the
  // camera march waited on (docs/performance.md, "Shorter chains").
  const double y = -x, y2 = y * y, y4 = y2 * y2;
  const double p01 = 1.0 + y, p23 = 0.5 + y * (1.0 / 6.0);
  const double p45 = 1.0 / 24.0 + y * (1.0 / 120.0), p67 = 1.0 / 720.0 + y * (1.0 / 5040.0);
  const double p89 = 1.0 / 40320.0 + y * (1.0 / 362880.0);
  return (p01 + y2 * p23) + y4 * ((p45 + y2 * p67) + y4 * p89);
}

}  // namespace obscura
