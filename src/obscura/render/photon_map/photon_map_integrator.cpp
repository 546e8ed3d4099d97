#include "obscura/render/photon_map/photon_map_integrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "obscura/core/sampling.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/direct_lighting.h"
#include "obscura/render/emission_absorption/emission_absorption.h"
#include "obscura/render/line_of_sight.h"

namespace obscura {
namespace {

using NodeArray = std::array<double, kMaxSpectralNodes>;
constexpr double kInf = std::numeric_limits<double>::infinity();

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

// Russian roulette deep in a cloud: once every node's transmittance to the
// camera is below kRouletteBelow, each further step survives with
// probability ½ and weight ×2 (unbiased), so an opaque cloud costs a few
// steps past the point where it stops mattering instead of its whole depth.
constexpr double kRouletteBelow = 1e-3;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

struct PhotonMapIntegrator::Workspace final : RayWorkspace {
  LineOfSight line_of_sight;
  std::vector<double> tau;  // optical depth to the camera along the march, per medium sample
  std::vector<PhotonNeighbour> neighbours;
  MediumPoint point, scratch;
};

PhotonMapIntegrator::PhotonMapIntegrator(const Scene& scene, const FrameSpectra& spectra,
                                         const ProcessGroup& processes,
                                         const PreparationProgress& progress)
    : scene_(scene), spectra_(spectra), settings_(scene.settings.photon_map) {
  PhotonTracingSettings tracing;
  tracing.photons = settings_.photons_per_node;
  tracing.store_first_scatter = settings_.pure;
  tracing.seed = scene.settings.seed;
  tracing.threads = scene.settings.threads;
  tracing.processes = &processes;
  // The progress over every map's photons.
  long long total = 0;
  for (const std::vector<SpectralNodes>& sensor_bands : spectra)
    for (const SpectralNodes& band : sensor_bands)
      total += tracing.photons * static_cast<long long>(band.size());
  PhotonTracingProgress tracing_progress(progress, total);
  tracing.on_traced = tracing_progress.on_traced();
  for (const std::vector<SpectralNodes>& sensor_bands : spectra) {
    const auto start = std::chrono::steady_clock::now();
    PreparationStats stats;
    std::vector<BandMaps>& sensor_maps = maps_.emplace_back();
    for (std::size_t b = 0; b < sensor_bands.size(); ++b) {
      BandMaps& band_maps = sensor_maps.emplace_back();
      for (std::size_t j = 0; j < sensor_bands[b].size(); ++j) {
        // Photon streams: one block of 2^40 per (band, node), apart from the
        // camera's per-pixel streams, which are below 2^40. A band of another
        // sensor with the same index and nodes gets the same photons.
        const std::uint64_t base = (static_cast<std::uint64_t>(b * 256 + j) + 1) << 40;
        const SpectralNode& node = sensor_bands[b].nodes()[j];
        NodeMap m;
        const auto t0 = std::chrono::steady_clock::now();
        m.traced = trace_photons(scene, node, base, tracing);
        tracing_progress.node_done(tracing.photons);
        stats.trace_seconds += seconds_since(t0);
        stats.walks += m.traced.walks;
        const auto t1 = std::chrono::steady_clock::now();
        m.map = std::make_unique<PhotonMap>(std::move(m.traced.photons));
        stats.build_seconds += seconds_since(t1);
        if (scene.sun.enabled) m.sun_irradiance = scene.sun.irradiance(node.wavelength_um);
        m.traced.photons.clear();
        stats.photons += m.map->size();
        stats.photon_bytes += m.map->memory_bytes();
        band_maps.push_back(std::move(m));
      }
    }
    stats.seconds = seconds_since(start);
    preparation_.push_back(stats);
  }
}

std::size_t PhotonMapIntegrator::photon_count() const {
  std::size_t n = 0;
  for (const PreparationStats& s : preparation_) n += s.photons;
  return n;
}

std::size_t PhotonMapIntegrator::memory_bytes() const {
  std::size_t n = 0;
  for (const PreparationStats& s : preparation_) n += s.photon_bytes;
  return n;
}

std::unique_ptr<RayWorkspace> PhotonMapIntegrator::make_workspace() const {
  auto ws = std::make_unique<Workspace>();
  ws->neighbours.reserve(static_cast<std::size_t>(settings_.k));
  return ws;
}

void PhotonMapIntegrator::begin_ray(const CameraRay& camera, RayWorkspace& workspace) const {
  static_cast<Workspace&>(workspace).line_of_sight.compute(scene_.medium.get(), camera);
}

void PhotonMapIntegrator::band_radiance(const CameraRay& camera, int sensor, int band, Rng& rng,
                                        RayWorkspace& workspace, double* radiance,
                                        double* transmittance) const {
  auto& ws = static_cast<Workspace&>(workspace);
  const SpectralNodes& nodes = spectra_[sensor][band];
  radiance_along(camera, nodes, maps_[sensor][band], rng, ws, radiance, 0);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    transmittance[i] = ws.line_of_sight.transmittance(nodes.nodes()[i]);
}

void PhotonMapIntegrator::radiance_along(const CameraRay& camera, const SpectralNodes& nodes,
                                         const BandMaps& maps, Rng& rng, Workspace& ws, double* out,
                                         int depth) const {
  const int n = static_cast<int>(nodes.size());
  // Emission and transmittance, exactly.
  NodeArray emission, transmittance, scattered, behind;
  std::fill_n(emission.begin(), n, 0.0);
  std::fill_n(transmittance.begin(), n, 1.0);
  std::fill_n(scattered.begin(), n, 0.0);
  integrate_emission(scene_.medium.get(), camera.ray, camera.t_end(), nodes,
                     scene_.settings.emission_quadrature, scene_.settings.relative_tolerance,
                     emission.data(), transmittance.data());
  if (scene_.medium) march_in_scattering(camera, nodes, maps, rng, ws, scattered.data());
  background(camera, nodes, maps, rng, ws, depth, behind.data());
  for (int j = 0; j < n; ++j) out[j] = emission[j] + transmittance[j] * behind[j] + scattered[j];
}

void PhotonMapIntegrator::march_in_scattering(const CameraRay& camera, const SpectralNodes& nodes,
                                              const BandMaps& maps, Rng& rng, Workspace& ws,
                                              double* scattered) const {
  const int n = static_cast<int>(nodes.size());
  const Medium& medium = *scene_.medium;
  const Ray& ray = camera.ray;
  ws.tau.assign(medium.wavelengths_um().size(), 0.0);
  double t_prev = 0.0, weight = 1.0;
  const Vec3 toward_camera = -ray.direction;
  medium.trace_majorants(ray, 0.0, camera.t_end(), [&](const MajorantSegment& piece) {
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
      medium.add_optical_depth(ray, t_prev, t, ws.tau.data());
      t_prev = t;
      // Transmittance to the camera per node, e^{−τ(0,t)}.
      NodeArray attenuation;
      double largest = 0.0;
      for (int j = 0; j < n; ++j) {
        attenuation[j] = std::exp(-nodes.nodes()[j].lerp()(ws.tau.data()));
        largest = std::max(largest, attenuation[j]);
      }
      if (largest < kRouletteBelow) {
        if (rng.uniform() >= 0.5) return false;
        weight *= 2.0;
      }
      const Vec3 x = ray.at(t);
      medium.coefficients_at(x, ws.point);
      for (int j = 0; j < n; ++j) {
        const SpectralNode& node = nodes.nodes()[j];
        const SpectralLerp lambda = node.lerp();
        const double sigma_s = lambda(ws.point.sigma_s.data());
        if (!(sigma_s > 0.0)) continue;
        if (attenuation[j] < 1e-12) continue;
        const HenyeyGreenstein phase(std::clamp(lambda(ws.point.g.data()), -0.999999, 0.999999));
        double source = 0.0;  // σs ∫ p L_in dω, W m⁻³ sr⁻¹ µm⁻¹
        if (!settings_.pure)
          source += single_scattering(x, ray.direction, node, maps[j], sigma_s, phase, rng, ws);
        const double sigma_t = sigma_s + lambda(ws.point.sigma_a.data());
        source +=
            photon_estimate(x, toward_camera, lambda, *maps[j].map, sigma_s, sigma_t, phase, ws);
        scattered[j] += weight * attenuation[j] * h * source;
      }
    }
    return true;
  });
}

double PhotonMapIntegrator::single_scattering(const Vec3& x, const Vec3& direction,
                                              const SpectralNode& node, const NodeMap& map,
                                              double sigma_s, const HenyeyGreenstein& phase,
                                              Rng& rng, Workspace& ws) const {
  const SpectralLerp lambda = node.lerp();
  double source = 0.0;
  if (scene_.sun.enabled) {
    const Vec3 to_sun = sample_sun_direction(scene_.sun, rng);
    source += sigma_s * phase.eval(direction, to_sun) * map.sun_irradiance *
              transmittance_to_infinity(scene_, x, to_sun, lambda, rng, ws.scratch);
  }
  // Environment: one direction from the phase function (weight 1).
  const Vec3 w = phase.sample(direction, rng.uniform(), rng.uniform(), nullptr);
  const Ray shadow{x, w};
  SurfaceHit other;
  const bool blocked = intersect_surfaces(scene_.surfaces, shadow, 1e-9, kInf, other);
  const double tr = estimate_transmittance(*scene_.medium, shadow, blocked ? other.t : kInf, lambda,
                                           rng, ws.scratch);
  if (tr > 0.0)
    source += sigma_s * tr *
              (blocked ? surface_radiance(scene_, other, shadow.at(other.t), node, rng, ws.scratch)
                       : scene_.sky.radiance(w, node.wavelength_um));
  return source;
}

double PhotonMapIntegrator::photon_estimate(const Vec3& x, const Vec3& toward_camera,
                                            const SpectralLerp& lambda, const PhotonMap& map,
                                            double sigma_s, double sigma_t,
                                            const HenyeyGreenstein& phase, Workspace& ws) const {
  // The search radius is also capped at a fraction of the local mean free
  // path: near a cloud's edge the fluence changes on that scale, and a wider
  // ball averages it with the brighter inside (a bias that the σs-weighted
  // volume below does not remove).
  const double r_max = std::min(settings_.max_radius_m, settings_.radius_mean_free_paths / sigma_t);
  map.k_nearest(x, settings_.k, r_max, ws.neighbours);
  if (ws.neighbours.empty()) return 0.0;
  const bool full = static_cast<int>(ws.neighbours.size()) == settings_.k;
  const double r2 = full ? static_cast<double>(ws.neighbours.back().distance2_m2) : r_max * r_max;
  // With k found, the k-th photon only sets the radius: (k − 1)/V is the
  // unbiased k-nearest-neighbour density (k/V overestimates by k/(k − 1));
  // with fewer, all lie strictly inside r_max.
  const std::size_t inside = full ? ws.neighbours.size() - 1 : ws.neighbours.size();
  double sum = 0.0;
  for (std::size_t q = 0; q < inside; ++q) {
    const Photon& p = map[ws.neighbours[q].index];
    sum += phase.eval(p.dir(), toward_camera) * p.power;
  }
  // Σ p ΔΦ over the ball ≈ L_in(x) ∫_ball σs: divide by that integral (times
  // σs(x)) rather than by σs(x) (4/3)π r³, so the part of the ball outside the
  // cloud does not dilute the estimate (boundary bias).
  const double r = std::sqrt(r2);
  double mean_sigma_s = 0.0;
  for (const Vec3& u : kBallPoints) {
    scene_.medium->coefficients_at(x + u * r, ws.scratch);
    mean_sigma_s += lambda(ws.scratch.sigma_s.data());
  }
  mean_sigma_s /= kBallPoints.size();
  if (!(mean_sigma_s > 0.0)) return 0.0;
  return sigma_s * sum / (4.0 / 3.0 * std::numbers::pi * r2 * r * mean_sigma_s);
}

void PhotonMapIntegrator::background(const CameraRay& camera, const SpectralNodes& nodes,
                                     const BandMaps& maps, Rng& rng, Workspace& ws, int depth,
                                     double* out) const {
  const int n = static_cast<int>(nodes.size());
  if (!camera.on_surface) {
    // The sky, and the sun's disc for camera rays.
    for (int j = 0; j < n; ++j) {
      const SpectralNode& node = nodes.nodes()[j];
      out[j] = scene_.sky.radiance(camera.ray.direction, node.wavelength_um);
      if (depth == 0 && scene_.settings.camera_sees_sun && scene_.sun.enabled &&
          dot(camera.ray.direction, scene_.sun.direction()) >= scene_.sun.cos_half_angle())
        out[j] += scene_.sun.radiance(node.wavelength_um);
    }
    return;
  }
  // A surface: its emission, the sun on it and, by one gathered ray,
  // everything else it reflects.
  const SurfaceHit& hit = camera.hit;
  const SurfaceMaterial& m = scene_.surfaces[hit.surface]->material();
  // ρ = 1 − ε per node; the sun and the gathering are skipped when no node reflects.
  NodeArray rho;
  double reflectance = 0.0;  // the largest ρ of the band
  for (int j = 0; j < n; ++j) {
    rho[j] = m.reflectance_at(nodes.nodes()[j].wavelength_um);
    reflectance = std::max(reflectance, rho[j]);
  }
  const Vec3 p = camera.ray.at(hit.t) + hit.normal * 1e-9;
  Vec3 to_sun;
  double cos_sun = 0.0;
  if (reflectance > 0.0 && scene_.sun.enabled) {
    to_sun = sample_sun_direction(scene_.sun, rng);
    cos_sun = dot(hit.normal, to_sun);
  }
  for (int j = 0; j < n; ++j) {
    const SpectralNode& node = nodes.nodes()[j];
    out[j] = (1.0 - rho[j]) * node.planck(m.temperature_k);
    if (cos_sun > 0.0)
      out[j] += rho[j] * std::numbers::inv_pi * cos_sun * maps[j].sun_irradiance *
                transmittance_to_infinity(scene_, p, to_sun, node.lerp(), rng, ws.scratch);
  }
  // Final gathering: ρ = 1 − ε times the radiance along one
  // cosine-distributed ray, found by this integrator itself (cloud light and
  // emission on the surface, other surfaces, the sky). The camera's surface
  // always gathers, weighted by ρ_j (a roulette there would multiply the noise
  // of a dark ground by 1/ρ); deeper gathers continue with probability ρ_max,
  // the band's largest ρ, and weight ρ_j / ρ_max, so the recursion ends
  // without bias.
  if (reflectance > 0.0 && depth < kMaxGatherDepth && (depth == 0 || rng.uniform() < reflectance)) {
    const Ray gather{
        p, local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
    NodeArray gathered;
    radiance_along(find_camera_ray_hit(scene_, gather), nodes, maps, rng, ws, gathered.data(),
                   depth + 1);
    for (int j = 0; j < n; ++j)
      out[j] += (depth == 0 ? rho[j] : rho[j] / reflectance) * gathered[j];
  }
}

}  // namespace obscura
