#pragma once
// An unbiased volumetric path tracer for the full RTE (DESIGN.md §3): the
// reference solution that faster methods are checked against. It handles
// volume emission σa B(T), scattering with the Henyey–Greenstein phase
// function, emitting and Lambertian-reflecting surfaces, the sky and the sun;
// the renderer uses it for "method": "path-tracer".
//
// One path at one spectral node:
//  * free flights by delta tracking against the medium's majorants;
//  * at a real collision the emission is scored with the collision estimator,
//    β (σa/σt) B(T) — its expectation over the free-flight density σt e^{−τ} is
//    ∫ e^{−τ} σa B ds — and the path continues with weight β·Λ, Λ = σs/σt,
//    in a direction drawn exactly from the HG phase function;
//  * a surface adds β ε B(T) and reflects with weight β (1 − ε) into a
//    cosine-distributed direction;
//  * at every collision and surface hit the sun is sampled directly (a
//    direction uniform over its disc, transmittance by ratio tracking, zero
//    behind a surface); escaping paths therefore see only the sky, except
//    camera rays, which see the sun's disc itself;
//  * under a table sky, at every collision and surface hit the sky is also
//    sampled directly (from Sky::sample, ratio-tracked transmittance), and an
//    escaping path's sky radiance and the direct sample are weighted by the
//    power heuristic (PathTracerSettings::sky_next_event);
//  * an escaping path adds β L_sky (MIS-weighted after a bounce);
//  * after a few bounces Russian roulette on β (survival probability
//    min(β, 0.99)) ends paths without bias.
#include "obscura/core/rng.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

struct PathTracerSettings {
  int russian_roulette_depth = 4;  // bounces before roulette starts
  int max_depth = 100000;          // a safety net; roulette ends paths long before
  // Camera rays that escape inside the sun's disc see the sun. Off when a
  // caller scores the unscattered sunlight itself (validate slab: T_direct).
  bool camera_sees_sun = true;
  // Sample the sky directly at every vertex (combined with the scattering
  // direction by multiple importance sampling), or find it only by escaping
  // paths. Both are unbiased. kAuto samples table skies only: for a uniform
  // blackbody sky the scattering direction is already distributed as well as
  // the sky's, and the extra ratio-tracked shadow ray only adds noise
  // (measured, docs/validation.md: furnace standard error 20× larger).
  enum class SkySampling { kAuto, kAlways, kNever };
  SkySampling sky_next_event = SkySampling::kAuto;
};

// One-sample estimate of the spectral radiance (W m⁻² sr⁻¹ µm⁻¹) arriving
// along -ray.direction at ray.origin, at spectral node `node`.
double trace_path(const Scene& scene, const Ray& ray, const SpectralNode& node, Rng& rng,
                  const PathTracerSettings& settings = {});

}  // namespace obscura
