// Cost of Mie theory: single-sphere evaluations per second at x = 1, 100 and
// 1e4, and size-distribution integrals (bulk optics) per second for a fog-oil
// smoke (docs/domain.md §2.2–2.3: lognormal, MMD 0.6 µm, σ_g 1.6, ρ 0.90 g/cm³) in
// the visible, at 1.064 µm and in the LWIR. Prints figures; asserts nothing.
//   bench_mie [--threads N] [--seconds S]
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_timer.h"
#include "obscura/core/parallel.h"
#include "obscura/optics/mie.h"
#include "obscura/optics/size_distribution.h"

using namespace obscura;
using bench::seconds_since;

namespace {

// Calls f repeatedly for at least `budget` seconds; returns calls per second.
template <class F>
double rate(F&& f, double budget) {
  long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0;
  do {
    f(calls++);
    elapsed = seconds_since(t0);
  } while (elapsed < budget);
  return calls / elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0;
  double budget = 0.5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--seconds")
      budget = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }

  std::printf("single sphere (one thread): evaluations per second\n");
  double checksum = 0;
  for (const std::complex<double> m :
       {std::complex<double>(1.33, 1e-8), std::complex<double>(1.75, 0.44)}) {
    for (double x : {1.0, 100.0, 1e4}) {
      // The size parameter moves by a part in 1e9 per call so nothing is cached.
      const double per_s = rate(
          [&](long i) { checksum += mie_sphere(x * (1 - 1e-9 * (i % 1000)), m).qext; }, budget);
      std::printf("  m = %.2f%+.2gi  x = %-6g %12.0f /s  (%.3g µs, %d terms)\n", m.real(), m.imag(),
                  x, per_s, 1e6 / per_s, mie_sphere(x, m).terms);
    }
  }

  const auto fog_oil = LognormalDistribution::from_mass_median_diameter(0.6, 1.6);
  std::printf(
      "\nbulk optics of fog oil (MMD 0.6 µm, σ_g 1.6, r_g %.3f µm, ρ 0.90 g/cm³), %d threads,\n"
      "default tolerance 1e-4: integrals per second\n",
      fog_oil.median_radius_um, resolve_thread_count(threads));
  struct Band {
    double lambda_um;
    std::complex<double> m;
  };
  for (const Band b : {Band{0.55, {1.48, 0}}, Band{1.064, {1.47, 0}}, Band{10.0, {1.47, 5e-3}}}) {
    BulkOptics out;
    const double per_s =
        rate([&](long) { out = bulk_optics(fog_oil, b.lambda_um, b.m, 0.9, {.threads = threads}); },
             budget);
    std::printf(
        "  λ %6.3f µm  m %.2f%+.3gi: α_ext %.4f m²/g  ω %.4f  g %.4f  (%d intervals)  %8.1f /s "
        "(%.3g ms)\n",
        b.lambda_um, b.m.real(), b.m.imag(), out.mass_extinction_m2_g, out.single_scattering_albedo,
        out.asymmetry, out.intervals, per_s, 1e3 / per_s);
  }
  std::printf("  (checksum %g)\n", checksum);
  return 0;
}
