// "Nice numbers" axis ticks and their labels for line plots (nice_ticks in
// report/line_plot.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/report/line_plot.h"

namespace obscura {
namespace {

// More is no axis a reader could use, and it bounds the ticks allocated.
constexpr int kMaxTargetTicks = 100;

// m × 10^e, computed so that the result is the double nearest the decimal
// (10^e is exact up to 10^22, and one multiplication or division of exact
// values rounds once): ticks then print and compare as the numbers they name.
double decimal(double m, int e) {
  if (std::abs(e) <= 22) {
    double p = 1.0;
    for (int i = 0; i < std::abs(e); ++i) p *= 10.0;
    return e >= 0 ? m * p : m / p;
  }
  return m * std::pow(10.0, e);
}

// A tick index range [first, last] of multiples of `step` inside [lo, hi]. The
// tolerance keeps ends such as 1/0.2 = 4.999... from being lost to rounding.
std::pair<double, double> multiples_inside(double lo, double hi, double step) {
  constexpr double kTolerance = 1e-9;
  return {std::ceil(lo / step - kTolerance), std::floor(hi / step + kTolerance)};
}

const char* const kSuperscripts[10] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};

std::string superscript(int n) {
  std::string out = n < 0 ? "⁻" : "";
  for (char c : std::to_string(std::abs(n))) out += kSuperscripts[c - '0'];
  return out;
}

// Typographic minus (U+2212): a hyphen is narrower than the digits and reads
// as a dash in tick labels.
std::string with_minus_sign(std::string s) {
  if (!s.empty() && s[0] == '-') s = "−" + s.substr(1);
  return s;
}

// "m×10ⁿ" with as many mantissa digits as the step `10^step_exponent` needs;
// "10ⁿ" for a mantissa of 1 when `bare_decades` (log axes, where decades are
// the norm; on a linear axis "1×10⁷" matches its neighbour "1.5×10⁷").
std::string power_label(double v, int step_exponent, bool bare_decades) {
  if (v == 0.0) return "0";
  const int e = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const std::string s = fmt::format("{:.{}e}", v, std::clamp(e - step_exponent, 0, 16));
  const size_t at = s.find('e');
  std::string mantissa = s.substr(0, at);
  const int exponent = std::atoi(s.c_str() + at + 1);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  if (bare_decades && mantissa == "1") return "10" + superscript(exponent);
  return with_minus_sign(mantissa) + "×10" + superscript(exponent);
}

// Labels for ticks at multiples of 10^step_exponent: plain decimals with the
// step's decimal places while the numbers stay short, powers of ten otherwise.
std::vector<std::string> linear_labels(const std::vector<double>& ticks, int step_exponent) {
  double largest = 0;
  for (double t : ticks) largest = std::max(largest, std::abs(t));
  const bool plain = largest == 0.0 || (largest >= 1e-4 && largest < 1e6);
  std::vector<std::string> labels;
  for (double t : ticks) {
    labels.push_back(plain ? with_minus_sign(fmt::format("{:.{}f}", t, std::max(0, -step_exponent)))
                           : power_label(t, step_exponent, /*bare_decades=*/false));
  }
  return labels;
}

AxisTicks linear_ticks(double lo, double hi, int target) {
  // The candidate steps around span/target: 1, 2, 5 × 10^(e-1 … e+1) always
  // bracket it, so the closest count is among them.
  const int e0 = static_cast<int>(std::floor(std::log10((hi - lo) / target)));
  double best_first = 0, best_last = -1;
  int best_m = 1, best_exponent = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int e = e0 - 1; e <= e0 + 1; ++e) {
    for (int m : {1, 2, 5}) {
      const double step = decimal(m, e);
      const auto [first, last] = multiples_inside(lo, hi, step);
      const double distance = std::abs(last - first + 1 - target);
      // Steps increase through the loop, so "<" prefers the smaller step on a
      // tie: one tick too many reads better than one too few.
      if (distance < best_distance) {
        best_distance = distance;
        best_m = m;
        best_first = first;
        best_last = last;
        best_exponent = e;
      }
    }
  }
  AxisTicks ticks;
  for (double i = best_first; i <= best_last; ++i) {
    ticks.major.push_back(decimal(i * best_m, best_exponent) + 0.0);  // + 0.0: no "−0"
  }
  ticks.labels = linear_labels(ticks.major, best_exponent);
  return ticks;
}

// Labels for m × 10^n on a log axis: decimals while every label is short
// (0.001 … 10000), powers of ten otherwise.
std::vector<std::string> log_labels(const std::vector<double>& ticks) {
  const bool plain =
      std::all_of(ticks.begin(), ticks.end(), [](double t) { return t >= 0.99e-3 && t < 1.01e4; });
  std::vector<std::string> labels;
  for (double t : ticks) {
    const int n = static_cast<int>(std::floor(std::log10(t) + 1e-9));
    labels.push_back(plain ? fmt::format("{:.{}f}", t, std::max(0, -n))
                           : power_label(t, n, /*bare_decades=*/true));
  }
  return labels;
}

AxisTicks log_ticks(double lo, double hi, int target) {
  const double l = std::log10(lo), h = std::log10(hi);
  const int n_lo = static_cast<int>(std::ceil(l - 1e-9));
  const int n_hi = static_cast<int>(std::floor(h + 1e-9));
  auto inside = [&](double v) { return v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9); };

  AxisTicks best;
  double best_distance = std::numeric_limits<double>::infinity();
  auto consider = [&](AxisTicks candidate) {
    const double distance = std::abs(static_cast<double>(candidate.major.size()) - target);
    // Ties go to the fewer ticks: a log axis crowded with labels reads badly.
    if (distance < best_distance ||
        (distance == best_distance && candidate.major.size() < best.major.size())) {
      best_distance = distance;
      best = std::move(candidate);
    }
  };

  // (a) Every k-th decade, k = 1, 2, 5, 10, 20, ... up to one tick or none.
  std::vector<int> strides;
  for (int j = 1; j <= n_hi - n_lo + 1; j *= 10) {
    for (int m : {1, 2, 5}) strides.push_back(m * j);
  }
  for (int k : strides) {
    AxisTicks c;
    for (int n = n_lo; n <= n_hi; ++n) {
      if (n % k == 0)
        c.major.push_back(decimal(1, n));
      else
        c.minor.push_back(decimal(1, n));
    }
    if (k == 1) {
      for (int n = n_lo - 1; n <= n_hi; ++n) {
        for (int m : {2, 5}) {
          if (inside(decimal(m, n))) c.minor.push_back(decimal(m, n));
        }
      }
      std::sort(c.minor.begin(), c.minor.end());
    }
    if (!c.major.empty()) consider(std::move(c));
  }
  // (b) 1, 2, 5 × every decade.
  {
    AxisTicks c;
    for (int n = n_lo - 1; n <= n_hi; ++n) {
      for (int m = 1; m <= 9; ++m) {
        const double v = decimal(m, n);
        if (!inside(v)) continue;
        (m == 1 || m == 2 || m == 5 ? c.major : c.minor).push_back(v);
      }
    }
    if (!c.major.empty()) consider(std::move(c));
  }
  if (!best.major.empty()) best.labels = log_labels(best.major);
  // (c) Under a decade the 1-2-5 ticks may be one or none: plain linear ticks
  // (a log axis that short is nearly linear anyway).
  if (hi / lo < 10) {
    AxisTicks c = linear_ticks(lo, hi, target);
    const double distance = std::abs(static_cast<double>(c.major.size()) - target);
    if (distance < best_distance) best = std::move(c);
  }
  return best;
}

}  // namespace

AxisTicks nice_ticks(double lo, double hi, int target_count, bool log) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || !std::isfinite(hi - lo)) {
    throw Error(fmt::format("nice_ticks: invalid range [{}, {}]", lo, hi));
  }
  if (target_count < 1 || target_count > kMaxTargetTicks) {
    throw Error(fmt::format("nice_ticks: target tick count must be 1..{}, got {}", kMaxTargetTicks,
                            target_count));
  }
  if (log && lo <= 0) {
    throw Error(fmt::format("nice_ticks: logarithmic range [{}, {}] must be positive", lo, hi));
  }
  // Steps must be normal doubles several digits above the rounding of the
  // ends, or ticks would repeat or be lost.
  if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi)) || hi - lo < 1e-280) {
    throw Error(fmt::format("nice_ticks: range [{}, {}] is too narrow to resolve", lo, hi));
  }
  return log ? log_ticks(lo, hi, target_count) : linear_ticks(lo, hi, target_count);
}

}  // namespace obscura
