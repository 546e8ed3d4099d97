#include "obscura/optics/mie.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "obscura/core/error.h"

namespace obscura {
namespace {

using cdouble = std::complex<double>;

// A denominator that is exactly zero is replaced by a tiny number, as in the
// modified Lentz algorithm (Thompson & Barnett 1986, J. Comput. Phys. 64, 490):
// the next step divides by it and the recurrence goes on with the right limit.
template <class T>
T nonzero(T v) {
  return v == T(0) ? T(1e-300) : v;
}

// Complex division by Smith's method (Smith 1962, CACM 5, 435): one real
// division, no overflow or underflow of |q|² for any representable operands.
// It is several times faster than the library's fully IEEE-special-cased
// __divdc3, which dominates the cost of a Mie evaluation otherwise; no
// operand here is infinite or NaN.
inline cdouble divide(cdouble p, cdouble q) {
  const double a = p.real(), b = p.imag(), c = q.real(), d = q.imag();
  if (std::abs(c) >= std::abs(d)) {
    const double r = d / c, t = 1.0 / (c + d * r);
    return {(a + b * r) * t, (b - a * r) * t};
  }
  const double r = c / d, t = 1.0 / (c * r + d);
  return {(a * r + b) * t, (b * r - a) * t};
}
inline double divide(double p, double q) { return p / q; }
inline cdouble reciprocal(cdouble q) { return divide(cdouble(1.0), q); }
inline double reciprocal(double q) { return 1.0 / q; }
inline double squared_magnitude(cdouble v) { return std::norm(v); }
inline double squared_magnitude(double v) { return v * v; }

// Shifted logarithmic derivative at the top index N,
//   D̃_N(z) = D_N(z) − (N + 1)/z,   D_n(z) = ψ_n'(z)/ψ_n(z),
// from the continued fraction for the Bessel-function ratio (Lentz 1976,
// Appl. Opt. 15, 668; used by Wiscombe's MIEV0 to start the downward
// recurrence): with D_N(z) = −N/z + J_{N−1/2}(z)/J_{N+1/2}(z) and
// J_{ν−1}/J_ν = 2ν/z − 1/(2(ν+1)/z − 1/(2(ν+2)/z − …)),
//   D̃_N(z) = −1/f,   f = b₀ − 1/(b₁ − 1/(b₂ − …)),   b_j = (2N + 3 + 2j)/z.
// Writing it for D̃ rather than D removes the leading (N+1)/z analytically,
// which keeps every digit when |z| ≪ 1 (see mie_sphere).
//
// Evaluated by the modified Lentz algorithm. The fraction is the downward
// recurrence unrolled, so it converges once the tail's influence has decayed:
// beyond the turning point j ≈ |z| − N, or sooner when Im z is large (the tail
// is then damped like e^{−2 Im z}). Convergence is accepted after three
// consecutive factors within 1e-15 of 1: one such factor can occur by chance
// where the partial fractions oscillate (real z below the turning point),
// three in a row cannot.
template <class T>
T shifted_log_derivative_top(T z, int n_top) {
  const double two_n3 = 2.0 * n_top + 3.0;
  const T inv_z = reciprocal(z);
  T f = nonzero(T(two_n3) * inv_z);
  T c = f;
  T d = T(0);
  const long max_iterations = 2 * static_cast<long>(std::abs(z)) + 100000;
  int hits = 0;
  for (long j = 1; j <= max_iterations; ++j) {
    const T b = (two_n3 + 2.0 * static_cast<double>(j)) * inv_z;
    d = reciprocal(nonzero(b - d));
    c = nonzero(b - reciprocal(c));
    const T delta = c * d;
    f *= delta;
    if (squared_magnitude(delta - T(1)) < 1e-30) {  // |Δ − 1| < 1e-15
      if (++hits == 3) return -reciprocal(f);
    } else {
      hits = 0;
    }
  }
  throw Error(fmt::format("Mie: the continued fraction for D_{}(z) did not converge at |z| = {}",
                          n_top, std::abs(z)));
}

// D̃_n(z) for n = 0 … N into out[0 … N], by the downward recurrence (Wiscombe
// 1979; Bohren & Huffman eq. 4.89, D_{n−1} = n/z − 1/(D_n + n/z)), rewritten
// for D̃_n = D_n − (n+1)/z:
//   D̃_{n−1}(z) = −z / (2n + 1 + z D̃_n(z)).
// Downward, the recurrence is stable for every complex z (Kattawar & Plass
// 1967, Appl. Opt. 6, 1377; Wiscombe 1979 §3).
template <class T>
void shifted_log_derivatives(T z, int n_top, T* out) {
  out[n_top] = shifted_log_derivative_top(z, n_top);
  for (int n = n_top; n >= 1; --n) out[n - 1] = -divide(z, nonzero((2.0 * n + 1.0) + z * out[n]));
}

void validate(double x, cdouble m) {
  if (!(std::isfinite(x) && x > 0.0))
    throw InputError("", "size_parameter", fmt::format("must be a finite number > 0, got {}", x));
  if (x > kMaxMieSizeParameter)
    throw InputError("", "size_parameter",
                     fmt::format("must be at most {:g} (got {:g}); use geometric optics beyond",
                                 kMaxMieSizeParameter, x));
  if (!(std::isfinite(m.real()) && m.real() > 0.0))
    throw InputError("", "refractive_index.real",
                     fmt::format("must be a finite number > 0, got {}", m.real()));
  if (!(std::isfinite(m.imag()) && m.imag() >= 0.0))
    throw InputError(
        "", "refractive_index.imag",
        fmt::format("must be a finite number >= 0 (k >= 0 is absorbing), got {}", m.imag()));
}

// Riccati–Bessel functions of the real argument (Bohren & Huffman §4.8):
// ψ_n(x) = x j_n(x), χ_n(x) = −x y_n(x), ξ_n = ψ_n − iχ_n, for n = 1, 2, …
// in turn.
// χ_n grows with n, so its upward recurrence χ_n = (2n−1)/x χ_{n−1} − χ_{n−2}
// (χ_{−1} = −sin x, χ_0 = cos x) is stable for every n.
// ψ_n is taken upward the same way (ψ_{−1} = cos x, ψ_0 = sin x) only while
// n ≤ x, where it oscillates and the recurrence keeps its absolute accuracy;
// for n > x it decays monotonically and upward recurrence loses a factor
// ~x² per step (at x = 1e-3, ψ_2 would keep 4 digits). There ψ_n has no
// zeros (the first zero of ψ_n lies beyond n + ½ + 1.85 (n + ½)^{1/3}), so it
// is taken from the downward ratios ψ_{n−1}/ψ_n = D_n(x) + n/x, i.e.
//   ψ_n = −ψ_{n−1} D̃_{n−1}(x),
// which keeps full relative accuracy for any x.
class RiccatiBessel {
 public:
  // dx: D̃_n(x) for n = 0 … the highest order asked for.
  RiccatiBessel(double x, const double* dx)
      : dx_(dx), inv_x_(1.0 / x), n_upward_(x >= 1.0 ? static_cast<int>(x) : 0) {
    const double sin_x = std::sin(x), cos_x = std::cos(x);
    psi_prev2_ = cos_x;
    psi_prev_ = sin_x;
    chi_prev2_ = -sin_x;
    chi_prev_ = cos_x;
    xi_prev_ = cdouble(psi_prev_, -chi_prev_);
  }

  // Whether order n is in the upward (oscillating, n ≤ x) range.
  bool upward(int n) const { return n <= n_upward_; }

  // Order n from orders n − 1 and n − 2.
  void compute(int n) {
    const double dn = n;
    psi_ = upward(n) ? (2.0 * dn - 1.0) * inv_x_ * psi_prev_ - psi_prev2_ : -psi_prev_ * dx_[n - 1];
    chi_ = (2.0 * dn - 1.0) * inv_x_ * chi_prev_ - chi_prev2_;
    xi_ = cdouble(psi_, -chi_);
  }
  // The order computed last becomes the previous one.
  void shift() {
    psi_prev2_ = psi_prev_;
    psi_prev_ = psi_;
    chi_prev2_ = chi_prev_;
    chi_prev_ = chi_;
    xi_prev_ = xi_;
  }

  double psi() const { return psi_; }
  double psi_prev() const { return psi_prev_; }
  cdouble xi() const { return xi_; }
  cdouble xi_prev() const { return xi_prev_; }

 private:
  const double* dx_;
  double inv_x_;
  int n_upward_;
  double psi_prev2_, psi_prev_, chi_prev2_, chi_prev_;
  cdouble xi_prev_;
  double psi_ = 0, chi_ = 0;
  cdouble xi_;
};

struct ScatteringCoefficients {
  cdouble a, b;
};

// Bohren & Huffman eq. 4.88:
//   a_n = [(D_n(mx)/m + n/x) ψ_n − ψ_{n−1}] / [(D_n(mx)/m + n/x) ξ_n − ξ_{n−1}]
//   b_n = [(m D_n(mx) + n/x) ψ_n − ψ_{n−1}] / [(m D_n(mx) + n/x) ξ_n − ξ_{n−1}].
// For n > x the numerators are rewritten with ψ_{n−1} = ψ_n (D_n(x) + n/x):
//   a_n numerator = ψ_n [D_n(mx)/m − D_n(x)],
//   b_n numerator = ψ_n [m D_n(mx) − D_n(x)] = ψ_n [m D̃_n(mx) − D̃_n(x)].
// In b_n both terms tend to (n+1)/x as x → 0 and their difference to
// (1 − m²) x/(2n+3): the shifted derivatives drop the (n+1)/x exactly, so
// no digits cancel. For n ≤ x the textbook form is kept, because D_n(x)
// has poles there (at the zeros of ψ_n) while the textbook form has none.
// dm_n, dx_n: D̃_n(mx), D̃_n(x).
ScatteringCoefficients scattering_coefficients(int n, const RiccatiBessel& rb, cdouble dm_n,
                                               double dx_n, cdouble m, cdouble inv_m,
                                               cdouble inv_mx, double inv_x) {
  const double dn = n;
  const double psi = rb.psi(), psi_prev = rb.psi_prev();
  const cdouble d_mx = dm_n + (dn + 1.0) * inv_mx;
  const cdouble da = d_mx * inv_m + dn * inv_x;
  const cdouble db = m * d_mx + dn * inv_x;
  cdouble num_a, num_b;
  if (rb.upward(n)) {
    num_a = da * psi - psi_prev;
    num_b = db * psi - psi_prev;
  } else {
    num_a = psi * (d_mx * inv_m - (dx_n + (dn + 1.0) * inv_x));
    num_b = psi * (m * dm_n - dx_n);
  }
  return {divide(num_a, da * rb.xi() - rb.xi_prev()), divide(num_b, db * rb.xi() - rb.xi_prev())};
}

// The series of Bohren & Huffman eqs. 4.61, 4.62, 4.82 and the asymmetry sum
// (p. 120):
//   Q_ext = (2/x²) Σ (2n+1) Re(a_n + b_n)
//   Q_sca = (2/x²) Σ (2n+1) (|a_n|² + |b_n|²)
//   Q_back = (1/x²) |Σ (2n+1) (−1)^n (a_n − b_n)|²
//   g Q_sca = (4/x²) [Σ n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1})
//                      + Σ (2n+1)/(n(n+1)) Re(a_n b*_n)]
class MieSums {
 public:
  // Whether term n is too small to change any sum: every contribution is
  // bounded by (2n+1)(|a_n| + |b_n|).
  bool negligible(int n, const ScatteringCoefficients& c) const {
    const double w = 2.0 * n + 1.0;
    return w * (std::abs(c.a) + std::abs(c.b)) <= 1e-17 * std::min(ext_, std::abs(back_));
  }

  // Adds term n (n = 1, 2, … in turn).
  void add(int n, const ScatteringCoefficients& c) {
    const double dn = n;
    const double w = 2.0 * dn + 1.0;
    const cdouble a = c.a, b = c.b;
    ext_ += w * (a.real() + b.real());
    sca_ += w * (std::norm(a) + std::norm(b));
    back_ += ((n % 2) ? -w : w) * (a - b);
    asym_ += w / (dn * (dn + 1.0)) * (a * std::conj(b)).real();
    if (n > 1)
      asym_ +=
          (dn - 1.0) * (dn + 1.0) / dn * (a_prev_ * std::conj(a) + b_prev_ * std::conj(b)).real();
    a_prev_ = a;
    b_prev_ = b;
  }

  MieEfficiencies efficiencies(double x, cdouble m) const {
    MieEfficiencies q;
    const double inv_x2 = 1.0 / (x * x);
    q.qext = 2.0 * inv_x2 * ext_;
    q.qsca = 2.0 * inv_x2 * sca_;
    // Absorption is the difference (the optical theorem, Bohren & Huffman eq.
    // 3.24); rounding can make it a few ulps of Q_ext negative, never physical.
    q.qabs = m.imag() == 0.0 ? 0.0 : std::max(0.0, q.qext - q.qsca);
    q.qback = std::norm(back_) * inv_x2;
    // sca_ underflows only for x below ~1e-50, where g is 0 to all digits.
    q.g = sca_ > 0.0 ? 2.0 * asym_ / sca_ : 0.0;
    return q;
  }

 private:
  double ext_ = 0, sca_ = 0, asym_ = 0;
  cdouble back_ = 0, a_prev_ = 0, b_prev_ = 0;
};

}  // namespace

int mie_term_count(double size_parameter) {
  if (!(std::isfinite(size_parameter) && size_parameter > 0.0))
    throw InputError("", "size_parameter",
                     fmt::format("must be a finite number > 0, got {}", size_parameter));
  return static_cast<int>(size_parameter + 4.05 * std::cbrt(size_parameter) + 2.0);
}

MieEfficiencies mie_sphere(double x, cdouble m) {
  validate(x, m);
  // Wiscombe's N terms converge Q_ext, Q_sca and g to ~1e-10 (Q_ext of
  // absorbing spheres is the slowest), but not the backscatter sum: its terms
  // are linear in a_n − b_n and alternate in sign, so stopping at N leaves
  // errors up to ~1e-5 relative at x ≳ 1e3. Measured against long-double sums
  // run to convergence, 1e-12 needs up to N + 2.25 x^{1/3} + 3 terms for
  // 1 ≤ x ≤ 2e4 (below x = 1, N already gives 1e-12). So the sums run past N
  // until a term no longer changes any of them, at most to N + 3 x^{1/3} + 3.
  const int n_terms = mie_term_count(x);
  const int n_max = n_terms + (x >= 1.0 ? static_cast<int>(3.0 * std::cbrt(x)) + 3 : 0);
  const cdouble mx = m * x;

  // D̃_n(mx) and D̃_n(x), n = 0 … n_max. Buffers are per thread and reused:
  // a size-distribution integral calls this thousands of times.
  thread_local std::vector<cdouble> dm;
  thread_local std::vector<double> dx;
  dm.resize(n_max + 1);
  dx.resize(n_max + 1);
  shifted_log_derivatives(mx, n_max, dm.data());
  shifted_log_derivatives(x, n_max, dx.data());

  RiccatiBessel rb(x, dx.data());
  const cdouble inv_m = reciprocal(m), inv_mx = reciprocal(mx);
  const double inv_x = 1.0 / x;
  MieSums sums;
  int n_summed = 0;
  for (int n = 1; n <= n_max; ++n) {
    rb.compute(n);
    const ScatteringCoefficients c =
        scattering_coefficients(n, rb, dm[n], dx[n], m, inv_m, inv_mx, inv_x);
    // Past N, stop at the first term too small to change any sum.
    if (n > n_terms && sums.negligible(n, c)) break;
    sums.add(n, c);
    n_summed = n;
    rb.shift();
  }
  MieEfficiencies q = sums.efficiencies(x, m);
  q.terms = n_summed;
  return q;
}

}  // namespace obscura
