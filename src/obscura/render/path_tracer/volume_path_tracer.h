#pragma once
// An unbiased volumetric path tracer for the full RTE (docs/physics.md): the
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
//    power heuristic (PathTracerSettings::sky_next_event, scene/render_settings.h);
//  * an escaping path adds β L_sky (MIS-weighted after a bounce);
//  * after a few bounces Russian roulette on β (survival probability
//    min(β, 0.99)) ends paths without bias.
#include "obscura/core/rng.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/integrator.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

// One-sample estimate of the spectral radiance (W m⁻² sr⁻¹ µm⁻¹) arriving
// along -ray.direction at ray.origin, at spectral node `node`, with the
// scene's settings (RenderSettings::path_tracer and camera_sees_sun). The
// first form takes the ray's first surface as found by the renderer.
double trace_path(const Scene& scene, const CameraRay& camera, const SpectralNode& node, Rng& rng);
double trace_path(const Scene& scene, const Ray& ray, const SpectralNode& node, Rng& rng);

}  // namespace obscura
