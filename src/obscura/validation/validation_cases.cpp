#include "obscura/validation/validation_cases.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/volume_path_tracer.h"

namespace obscura {
namespace {

struct MeanEstimate {
  double mean = 0, stderr_mean = 0;
  long long samples = 0;
};

// Mean and standard error of draws of `sample`, draw i with its own pcg32
// stream. With o.samples > 0 exactly that many draws; with 0, batches until the
// standard error is below `target_stderr` (at most kMaxAutoSamples draws).
constexpr int kAutoBatch = 50000;
constexpr long long kMaxAutoSamples = 50000000;

template <typename Sample>
MeanEstimate estimate(const ValidationOptions& o, double target_stderr, std::uint64_t stream_base,
                      Sample&& sample) {
  double sum = 0, sum2 = 0;
  long long n = 0;
  MeanEstimate e;
  while (true) {
    const long long batch = o.samples > 0 ? o.samples : kAutoBatch;
    for (long long i = 0; i < batch; ++i, ++n) {
      Rng rng(o.seed, stream_base + static_cast<std::uint64_t>(n));
      const double x = sample(rng);
      sum += x;
      sum2 += x * x;
    }
    e.mean = sum / n;
    const double var = n > 1 ? std::max(0.0, sum2 / n - e.mean * e.mean) * n / (n - 1) : 0.0;
    e.stderr_mean = std::sqrt(var / n);
    e.samples = n;
    if (o.samples > 0 || e.stderr_mean <= target_stderr || n >= kMaxAutoSamples) return e;
  }
}

ValidationRow row(std::string case_name, std::string quantity, double reference, MeanEstimate e,
                  double tolerance) {
  ValidationRow r{std::move(case_name), std::move(quantity), reference, e.mean, e.stderr_mean,
                  tolerance, false, e.samples};
  const double diff = std::abs(e.mean - reference);
  r.pass = diff <= std::max(3.0 * e.stderr_mean, tolerance * std::abs(reference)) &&
           e.stderr_mean <= tolerance * std::abs(reference);
  return r;
}

// The spectral node of a single wavelength for a medium with samples `w`.
SpectralNode monochromatic(double wavelength_um, const std::vector<double>& w) {
  const SpectralNodes nodes(
      BandQuadrature(Band::flat("mono", wavelength_um - 1e-6, wavelength_um + 1e-6), 1, 0.0), w);
  return nodes.nodes()[0];
}

void check(const std::string& field, double v, double lo, double hi, const char* what) {
  if (!(std::isfinite(v) && v >= lo && v <= hi))
    throw InputError("", field, fmt::format("{} (got {})", what, v));
}

void check_options(const ValidationOptions& o) {
  if (o.samples != 0 && o.samples < 2)
    throw InputError("", "--samples", "must be at least 2 (or 0: until the standard error is small enough)");
}

// Half the tolerance: the automatic sample count resolves a bias of `tolerance`.
double target(double tolerance, double reference) { return 0.5 * tolerance * std::abs(reference); }

// A direction through the centre of the unit cube, spread over the sphere by
// the stream so that every face and angle is exercised.
Ray ray_through_cube(Rng& rng) {
  const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * std::numbers::pi * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
  return Ray{Vec3(0.5, 0.5, 0.5) - d * 3.0, d};
}

}  // namespace

std::vector<ValidationRow> validate_furnace(double tau, double g, const ValidationOptions& o) {
  check_options(o);
  check("--tau", tau, 0.0, 1e3, "optical thickness must lie in [0, 1000]");
  check("--g", g, -0.999, 0.999, "g must lie in [-0.999, 0.999]");
  Scene scene;
  scene.sky.temperature_k = 300.0;
  scene.medium = std::make_shared<HomogeneousMedium>(BBox3({0, 0, 0}, {1, 1, 1}), std::vector<double>{10.0},
                                                     std::vector<double>{0.0}, std::vector<double>{tau},
                                                     std::vector<double>{g}, 0.0);
  const SpectralNode node = monochromatic(10.0, scene.medium->wavelengths_um());
  const double l0 = planck_radiance(10.0, 300.0);
  const MeanEstimate e = estimate(o, target(0.005, 1.0), 0, [&](Rng& rng) {
    const Ray ray = ray_through_cube(rng);
    return trace_path(scene, ray, node, rng) / l0;
  });
  return {row(fmt::format("furnace tau={} g={}", tau, g), "radiance / L0", 1.0, e, 0.005)};
}

std::vector<ValidationRow> validate_equilibrium(double albedo, double tau, double g,
                                                double temperature_k, const ValidationOptions& o) {
  check_options(o);
  check("--albedo", albedo, 0.0, 1.0, "albedo must lie in [0, 1]");
  check("--tau", tau, 0.0, 1e3, "optical thickness must lie in [0, 1000]");
  check("--g", g, -0.999, 0.999, "g must lie in [-0.999, 0.999]");
  check("--temperature", temperature_k, 1.0, 1e4, "temperature must lie in [1, 10000] K");
  Scene scene;
  scene.sky.temperature_k = temperature_k;
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{temperature_k, 0.5}, -1.0));
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({0, 0, 0}, {1, 1, 1}), std::vector<double>{4.0}, std::vector<double>{tau * (1 - albedo)},
      std::vector<double>{tau * albedo}, std::vector<double>{g}, temperature_k);
  const SpectralNode node = monochromatic(4.0, scene.medium->wavelengths_um());
  const double b = planck_radiance(4.0, temperature_k);
  const MeanEstimate e = estimate(o, target(0.005, 1.0), 0, [&](Rng& rng) {
    const Ray ray = ray_through_cube(rng);
    return trace_path(scene, ray, node, rng) / b;
  });
  return {row(fmt::format("equilibrium albedo={} tau={} g={} T={}", albedo, tau, g, temperature_k),
              "radiance / B(T)", 1.0, e, 0.005)};
}

std::vector<ValidationRow> validate_emitting_slab(double tau, double temperature_k,
                                                  const ValidationOptions& o) {
  check_options(o);
  check("--tau", tau, 0.0, 50.0, "optical thickness must lie in [0, 50]");
  check("--temperature", temperature_k, 1.0, 1e4, "temperature must lie in [1, 10000] K");
  Scene scene;
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-1e5, -1e5, 0}, {1e5, 1e5, 1}), std::vector<double>{10.0}, std::vector<double>{tau},
      std::vector<double>{0.0}, std::vector<double>{0.0}, temperature_k);
  const SpectralNode node = monochromatic(10.0, scene.medium->wavelengths_um());
  const double reference = -std::expm1(-tau);
  const double b = planck_radiance(10.0, temperature_k);
  const MeanEstimate e = estimate(o, target(0.005, reference), 0, [&](Rng& rng) {
    return trace_path(scene, Ray{{0, 0, 2}, {0, 0, -1}}, node, rng) / b;
  });
  return {row(fmt::format("emitting-slab tau={} T={}", tau, temperature_k), "radiance / B(T)",
              reference, e, 0.005)};
}

std::vector<ValidationRow> validate_single_scatter(double tau, double g, const ValidationOptions& o) {
  check_options(o);
  check("--tau", tau, 1e-6, 0.01, "a single-scattering slab must be optically thin: tau in [1e-6, 0.01]");
  check("--g", g, -0.999, 0.999, "g must lie in [-0.999, 0.999]");
  Scene scene;
  scene.sun.enabled = true;
  scene.sun.azimuth_deg = 90.0;
  scene.sun.elevation_deg = 50.0;
  const double d = 1.0, sigma_s = tau / d;
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-1e5, -1e5, 0}, {1e5, 1e5, d}), std::vector<double>{0.55}, std::vector<double>{0.0},
      std::vector<double>{sigma_s}, std::vector<double>{g}, 0.0);
  const SpectralNode node = monochromatic(0.55, scene.medium->wavelengths_um());
  const Vec3 view = normalize(Vec3(-0.3, 0.2, 1.0));
  const double mu = view.z, mu0 = scene.sun.direction().z;
  const double cos_scatter = dot(view, scene.sun.direction());
  const double p =
      (1 - g * g) / (4 * std::numbers::pi * std::pow(1 + g * g - 2 * g * cos_scatter, 1.5));
  const double a = sigma_s * (mu / mu0 - 1.0);
  const double e_sun = scene.sun.irradiance(0.55);
  // L = σs p E e^{−τ/μ0} (e^{a d/μ} − 1)/a, the single-scattered radiance below the slab.
  const double reference = sigma_s * p * std::exp(-tau / mu0) * std::expm1(a * d / mu) / a;
  const MeanEstimate e = estimate(o, target(0.01 + tau, reference), 0, [&](Rng& rng) {
    return trace_path(scene, Ray{{0, 0, -1}, view}, node, rng) / e_sun;
  });
  // Multiple scattering adds O(τ) relative: the tolerance allows 1 % + τ.
  return {row(fmt::format("single-scatter tau={} g={}", tau, g), "radiance / E_sun", reference, e,
              0.01 + tau)};
}

std::vector<ValidationRow> validate_puff_transmittance(const ValidationOptions& o) {
  check_options(o);
  GaussianPuffSpec spec;
  spec.center_m = {1.0, -2.0, 5.0};
  spec.radius_m = 2.0;
  spec.extent_radii = 4.0;
  spec.resolution = 128;
  spec.peak_sigma_a = {0.3};
  spec.peak_sigma_s = {0.2};
  spec.g = {0.0};
  const GridMedium medium(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
  const SpectralLerp lambda = SpectralLerp::at(medium.wavelengths_um(), 10.0);
  const Ray rays[] = {{{-20, -2.0, 5.0}, {1, 0, 0}},
                      {{-20, -1.3, 5.9}, normalize(Vec3(1, 0.05, -0.02))},
                      {{1.0, -2.0, -20.0}, normalize(Vec3(0.5, 0.5, 25.0))}};
  std::vector<ValidationRow> rows;
  for (int r = 0; r < 3; ++r) {
    double t0 = 0, t1 = 1e9;
    medium.bounds().intersect(rays[r], t0, t1);
    const double tau = 0.5 * gaussian_puff_line_integral(spec, rays[r], t0, t1);
    MediumPoint scratch;
    const double reference = std::exp(-tau);
    const MeanEstimate e = estimate(o, target(0.005, reference), static_cast<std::uint64_t>(r) << 40,
                                    [&](Rng& rng) {
                                      return estimate_transmittance(medium, rays[r], 1e9, lambda,
                                                                    rng, scratch);
                                    });
    rows.push_back(row(fmt::format("puff-transmittance ray {}", r + 1), "transmittance", reference,
                       e, 0.005));
  }
  return rows;
}

}  // namespace obscura
