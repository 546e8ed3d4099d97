#include "obscura/render/photon_map/photon_map_integrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/direct_lighting.h"
#include "obscura/render/emission_absorption/emission_absorption.h"

namespace obscura {
namespace {

// 64 fixed points that sample the unit ball with equal weights: 4 shells of
// equal volume (mid-shell radii ((i + ½)/4)^{1/3}), 16 directions each on a
// Fibonacci sphere turned by the golden angle from shell to shell. Fixed, so
// the estimate is deterministic; fine enough that the share of a ball cut by
// a cloud's edge is right to a few per cent.
const std::array<Vec3, 64> kBallPoints = [] {
  std::array<Vec3, 64> pts;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int shell = 0; shell < 4; ++shell) {
    const double radius = std::cbrt((shell + 0.5) / 4.0);
    for (int i = 0; i < 16; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / 16.0, rho = std::sqrt(1.0 - z * z);
      const double phi = golden * i + shell * golden * 0.5;
      pts[shell * 16 + i] = Vec3(rho * std::cos(phi), rho * std::sin(phi), z) * radius;
    }
  }
  return pts;
}();

// Gathered rays from surface to surface end here (roulette ends them long before).
constexpr int kMaxGatherDepth = 16;

}  // namespace

PhotonMapIntegrator::PhotonMapIntegrator(const Scene& scene,
                                         const std::vector<SpectralNodes>& band_nodes,
                                         const PhotonMapSettings& settings, std::uint64_t seed,
                                         int threads)
    : scene_(scene), band_nodes_(band_nodes), settings_(settings) {
  PhotonTracingSettings tracing;
  tracing.photons = settings.photons_per_node;
  tracing.store_first_scatter = settings.pure;
  tracing.seed = seed;
  tracing.threads = threads;
  maps_.resize(band_nodes.size());
  for (std::size_t b = 0; b < band_nodes.size(); ++b) {
    for (std::size_t j = 0; j < band_nodes[b].size(); ++j) {
      // Photon streams: one block of 2^40 per (band, node), apart from the
      // camera's per-pixel streams, which are below 2^40.
      const std::uint64_t base = (static_cast<std::uint64_t>(b * 256 + j) + 1) << 40;
      NodeMap m;
      const auto t0 = std::chrono::steady_clock::now();
      m.traced = trace_photons(scene, band_nodes[b].nodes()[j], base, tracing);
      const auto t1 = std::chrono::steady_clock::now();
      m.map = std::make_unique<PhotonMap>(std::move(m.traced.photons));
      if (scene.sun.enabled)
        m.sun_irradiance = scene.sun.irradiance(band_nodes[b].nodes()[j].wavelength_um);
      tracing_seconds_ += std::chrono::duration<double>(t1 - t0).count();
      build_seconds_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      m.traced.photons.clear();
      maps_[b].push_back(std::move(m));
    }
  }
}

std::size_t PhotonMapIntegrator::photon_count() const {
  std::size_t n = 0;
  for (const auto& band : maps_)
    for (const auto& m : band) n += m.map->size();
  return n;
}

std::size_t PhotonMapIntegrator::memory_bytes() const {
  std::size_t n = 0;
  for (const auto& band : maps_)
    for (const auto& m : band) n += m.map->memory_bytes();
  return n;
}

void PhotonMapIntegrator::radiance(const Ray& ray, int band, Rng& rng, double* out,
                                   int depth) const {
  const SpectralNodes& nodes = band_nodes_[band];
  const int n = static_cast<int>(nodes.size());
  const Medium* medium = scene_.medium.get();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  SurfaceHit hit;
  const bool on_surface = intersect_surfaces(scene_.surfaces, ray, 0.0, kInf, hit);
  const double t_max = on_surface ? hit.t : kInf;

  // Emission and transmittance, exactly.
  std::vector<double> emission(n, 0.0), transmittance(n, 1.0), scattered(n, 0.0);
  integrate_emission_absorption(medium, ray, t_max, nodes, scene_.settings.relative_tolerance,
                                emission.data(), transmittance.data());

  MediumPoint point, scratch;
  if (medium) {
    std::vector<double> tau(medium->wavelengths_um().size(), 0.0);
    std::vector<PhotonNeighbour> neighbours;
    double t_prev = 0.0;
    const Vec3 toward_camera = -ray.direction;
    // Russian roulette deep in a cloud: once every node's transmittance to the
    // camera is below kRouletteBelow, each further step survives with
    // probability ½ and weight ×2 (unbiased), so an opaque cloud costs a few
    // steps past the point where it stops mattering instead of its whole depth.
    constexpr double kRouletteBelow = 1e-3;
    double weight = 1.0;
    medium->trace_majorants(ray, 0.0, t_max, [&](const MajorantSegment& piece) {
      double majorant = 0.0;
      for (int k = 0; k < piece.spectral_count; ++k)
        majorant = std::max(majorant, piece.sigma_majorant[k]);
      if (!(majorant > 0.0)) return true;
      const double length = piece.t_end - piece.t_begin;
      const double target = std::min(settings_.step_m, 0.5 / majorant);
      const int count = std::max(1, static_cast<int>(std::ceil(length / target)));
      const double h = length / count;
      for (int i = 0; i < count; ++i) {
        const double t = piece.t_begin + (i + rng.uniform()) * h;
        medium->add_optical_depth(ray, t_prev, t, tau.data());
        t_prev = t;
        // Transmittance to the camera per node, e^{−τ(0,t)}.
        std::array<double, kMaxSpectralNodes> attenuation;
        double largest = 0.0;
        for (int j = 0; j < n; ++j) {
          attenuation[j] = std::exp(-nodes.nodes()[j].lerp()(tau.data()));
          largest = std::max(largest, attenuation[j]);
        }
        if (largest < kRouletteBelow) {
          if (rng.uniform() >= 0.5) return false;
          weight *= 2.0;
        }
        const Vec3 x = ray.at(t);
        medium->coefficients_at(x, point);
        for (int j = 0; j < n; ++j) {
          const SpectralNode& node = nodes.nodes()[j];
          const SpectralLerp lambda = node.lerp();
          const double sigma_s = lambda(point.sigma_s.data());
          if (!(sigma_s > 0.0)) continue;
          if (attenuation[j] < 1e-12) continue;
          const HenyeyGreenstein phase(std::clamp(lambda(point.g.data()), -0.999999, 0.999999));
          double source = 0.0;  // σs ∫ p L_in dω, W m⁻³ sr⁻¹ µm⁻¹
          if (!settings_.pure) {
            if (scene_.sun.enabled) {
              const Vec3 to_sun = sample_sun_direction(scene_.sun, rng);
              source += sigma_s * phase.eval(ray.direction, to_sun) *
                        maps_[band][j].sun_irradiance *
                        transmittance_to_infinity(scene_, x, to_sun, lambda, rng, scratch);
            }
            // Environment: one direction from the phase function (weight 1).
            const Vec3 w = phase.sample(ray.direction, rng.uniform(), rng.uniform(), nullptr);
            const Ray shadow{x, w};
            SurfaceHit other;
            const bool blocked = intersect_surfaces(scene_.surfaces, shadow, 1e-9, kInf, other);
            const double tr = estimate_transmittance(*medium, shadow, blocked ? other.t : kInf,
                                                     lambda, rng, scratch);
            if (tr > 0.0)
              source +=
                  sigma_s * tr *
                  (blocked ? surface_radiance(scene_, other, shadow.at(other.t), node, rng, scratch)
                           : scene_.sky.radiance(w, node.wavelength_um));
          }
          // Multiple (or, pure, all) scattering from the k nearest photons.
          const PhotonMap& map = *maps_[band][j].map;
          // The search radius is also capped at a fraction of the local mean
          // free path: near a cloud's edge the fluence changes on that scale,
          // and a wider ball averages it with the brighter inside (a bias that
          // the σs-weighted volume below does not remove).
          const double sigma_t = sigma_s + lambda(point.sigma_a.data());
          const double r_max =
              std::min(settings_.max_radius_m, settings_.radius_mean_free_paths / sigma_t);
          map.k_nearest(x, settings_.k, r_max, neighbours);
          if (!neighbours.empty()) {
            const double r2 = static_cast<int>(neighbours.size()) == settings_.k
                                  ? static_cast<double>(neighbours.back().distance2_m2)
                                  : r_max * r_max;
            // With k found, the k-th photon only sets the radius: (k − 1)/V is
            // the unbiased k-nearest-neighbour density (k/V overestimates by
            // k/(k − 1)); with fewer, all lie strictly inside r_max.
            const std::size_t inside = static_cast<int>(neighbours.size()) == settings_.k
                                           ? neighbours.size() - 1
                                           : neighbours.size();
            double sum = 0.0;
            for (std::size_t q = 0; q < inside; ++q) {
              const Photon& p = map[neighbours[q].index];
              sum += phase.eval(p.dir(), toward_camera) * p.power;
            }
            // Σ p ΔΦ over the ball ≈ L_in(x) ∫_ball σs: divide by that integral
            // (times σs(x)) rather than by σs(x) (4/3)π r³, so the part of the
            // ball outside the cloud does not dilute the estimate (boundary bias).
            const double r = std::sqrt(r2);
            double mean_sigma_s = 0.0;
            for (const Vec3& u : kBallPoints) {
              medium->coefficients_at(x + u * r, scratch);
              mean_sigma_s += lambda(scratch.sigma_s.data());
            }
            mean_sigma_s /= kBallPoints.size();
            if (mean_sigma_s > 0.0)
              source += sigma_s * sum / (4.0 / 3.0 * std::numbers::pi * r2 * r * mean_sigma_s);
          }
          scattered[j] += weight * attenuation[j] * h * source;
        }
      }
      return true;
    });
  }

  // The background: a surface (its emission, the sun on it and, by one
  // gathered ray, everything else it reflects), or the sky and the sun's disc.
  std::vector<double> background(n, 0.0);
  if (on_surface) {
    const SurfaceMaterial& m = scene_.surfaces[hit.surface]->material();
    // ρ = 1 − ε per node; the sun and the gathering are skipped when no node reflects.
    std::array<double, kMaxSpectralNodes> rho;
    double reflectance = 0.0;  // the largest ρ of the band
    for (int j = 0; j < n; ++j) {
      rho[j] = m.reflectance_at(nodes.nodes()[j].wavelength_um);
      reflectance = std::max(reflectance, rho[j]);
    }
    const Vec3 p = ray.at(hit.t) + hit.normal * 1e-9;
    Vec3 to_sun;
    double cos_sun = 0.0;
    if (reflectance > 0.0 && scene_.sun.enabled) {
      to_sun = sample_sun_direction(scene_.sun, rng);
      cos_sun = dot(hit.normal, to_sun);
    }
    for (int j = 0; j < n; ++j) {
      const SpectralNode& node = nodes.nodes()[j];
      background[j] = (1.0 - rho[j]) * node.planck(m.temperature_k);
      if (cos_sun > 0.0)
        background[j] += rho[j] * std::numbers::inv_pi * cos_sun * maps_[band][j].sun_irradiance *
                         transmittance_to_infinity(scene_, p, to_sun, node.lerp(), rng, scratch);
    }
    // Final gathering: ρ = 1 − ε times the radiance along one
    // cosine-distributed ray, found by this integrator itself (cloud light and
    // emission on the surface, other surfaces, the sky). The camera's surface
    // always gathers, weighted by ρ_j (a roulette there would multiply the
    // noise of a dark ground by 1/ρ); deeper gathers continue with probability
    // ρ_max, the band's largest ρ, and weight ρ_j / ρ_max, so the recursion
    // ends without bias.
    if (reflectance > 0.0 && depth < kMaxGatherDepth &&
        (depth == 0 || rng.uniform() < reflectance)) {
      const Ray gather{
          p, local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
      std::vector<double> gathered(n, 0.0);
      radiance(gather, band, rng, gathered.data(), depth + 1);
      for (int j = 0; j < n; ++j)
        background[j] += (depth == 0 ? rho[j] : rho[j] / reflectance) * gathered[j];
    }
  } else {
    for (int j = 0; j < n; ++j) {
      const SpectralNode& node = nodes.nodes()[j];
      background[j] = scene_.sky.radiance(ray.direction, node.wavelength_um);
      if (depth == 0 && settings_.camera_sees_sun && scene_.sun.enabled &&
          dot(ray.direction, scene_.sun.direction()) >= scene_.sun.cos_half_angle())
        background[j] += scene_.sun.radiance(node.wavelength_um);
    }
  }
  for (int j = 0; j < n; ++j)
    out[j] = emission[j] + transmittance[j] * background[j] + scattered[j];
}

}  // namespace obscura
