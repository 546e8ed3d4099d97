#pragma once
// Lorenz–Mie efficiencies of a homogeneous sphere (Bohren & Huffman 1983,
// "Absorption and Scattering of Light by Small Particles", ch. 4 and app. A;
// Wiscombe 1979, NCAR TN-140+STR, and Appl. Opt. 19, 1505, 1980). The method,
// its equations and its validation are in docs/optics.md.
//
// Convention: refractive index m = n + i·k relative to the surrounding medium,
// k ≥ 0 absorbing (Bohren & Huffman's e^{−iωt} time dependence; MIEV0 and
// miepython write the same sphere as n − i·k). Size parameter x = 2π r / λ with
// λ the wavelength in the surrounding medium.
#include <complex>

namespace obscura {

struct MieEfficiencies {
  double qext = 0;   // extinction efficiency C_ext / (π r²)
  double qsca = 0;   // scattering efficiency C_sca / (π r²)
  double qabs = 0;   // absorption efficiency, qext − qsca (≥ 0; exactly 0 when k = 0)
  double qback = 0;  // backscattering (radar) efficiency 4π (dC_sca/dΩ)(180°) / (π r²)
  double g = 0;      // asymmetry parameter, mean cosine of the scattering angle
  int terms = 0;     // partial waves summed: at least mie_term_count(x), see mie.cpp
};

// Largest size parameter mie_sphere accepts. The cost and memory grow as x
// (about 24 bytes per term); at 1e6 the efficiencies are within 1e-3 of their
// geometric-optics limits, where Mie theory is no longer the tool of choice.
inline constexpr double kMaxMieSizeParameter = 1e6;

// Wiscombe's number of partial waves, N = ⌊x + 4.05 x^{1/3} + 2⌋ (Appl. Opt.
// 19, 1505, eq. 5; the 8 < x < 4200 form, which is at least as large as the
// forms for the other ranges, so it is used everywhere). mie_sphere sums at
// least N terms, and for x ≥ 1 goes on (at most 3 x^{1/3} + 3 more) while the
// terms still change a sum: the backscatter sum needs them.
int mie_term_count(double size_parameter);

// Efficiencies of a sphere with size parameter x = 2πr/λ and relative index m.
// Accurate to about 1e-10 relative (docs/optics.md) for 1e-6 ≤ x ≤ 2e4 and
// from weakly to strongly absorbing indices (tested to m = 10 + 10i).
// Throws InputError (file "", field "size_parameter", "refractive_index.real"
// or "refractive_index.imag") unless 0 < x ≤ kMaxMieSizeParameter, n > 0 and
// k ≥ 0, all finite.
MieEfficiencies mie_sphere(double size_parameter, std::complex<double> m);

}  // namespace obscura
