#pragma once
// Light arriving from outside the cloud, estimated directly (one sample each,
// unbiased): what the photon-map integrator's ray marcher and photon emitter
// use for "the environment" (docs/physics.md, "Volume photon mapping").
//
//  * surface_radiance: the radiance a grey Lambertian surface point sends,
//      ε B(T) + (1 − ε)/π [E_sun cos θ_sun T_sun + π L_sky-or-surface(ω) T(ω)],
//    the sun by one direction over its disc, the rest of the hemisphere by one
//    cosine-distributed direction that finds the sky or another surface's
//    emission ε B(T); transmittances through the cloud by ratio tracking, so
//    the cloud's shadow on the ground is included. Light that the cloud
//    scatters or emits onto the surface is not (the photon map has no surface
//    photons: docs/physics.md states the limitation).
//  * environment_radiance: radiance arriving at a point from direction
//    `toward` when nothing of the cloud is in between: the surface the ray
//    hits (surface_radiance) or else the sky; the sun's disc is not included
//    (it is sampled on its own).
#include "obscura/core/rng.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

// Transmittance from `origin` along `direction` to infinity: zero when a
// surface is in the way, else ratio tracking through the scene's medium.
double transmittance_to_infinity(const Scene& scene, const Vec3& origin, const Vec3& direction,
                                 const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch);

// A direction uniform over the sun's disc.
Vec3 sample_sun_direction(const Sun& sun, Rng& rng);

double surface_radiance(const Scene& scene, const SurfaceHit& hit, const Vec3& position,
                        const SpectralNode& node, Rng& rng, MediumPoint& scratch);

double environment_radiance(const Scene& scene, const Vec3& origin, const Vec3& toward,
                            const SpectralNode& node, Rng& rng, MediumPoint& scratch);

}  // namespace obscura
