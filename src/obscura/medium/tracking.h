#pragma once
// Distance sampling and transmittance estimation against a medium's
// majorants, written once for every integrator (pbrt-v4 SampleT_maj; docs/conventions.md
// §2): the path tracer, the photon tracer and later GPU kernels all call these.
//
// Both walk the piecewise-constant majorant σ̄ of Medium::trace_majorants and
// draw tentative collisions with rate σ̄ (exponential steps, restarted at each
// piece boundary: exact, as the exponential is memoryless). At a tentative
// collision at t the true extinction σt(t) is evaluated:
//  * delta tracking (Woodcock et al. 1965) accepts it as a real collision with
//    probability σt/σ̄, so real collisions have density σt(t) e^{−τ(0,t)};
//  * ratio tracking (Cramer 1978; Novák, Selle & Jarosz 2014) multiplies the
//    weight by 1 − σt/σ̄ and goes on: an unbiased estimate of e^{−τ}.
#include <optional>

#include "obscura/core/rng.h"
#include "obscura/medium/medium.h"
#include "obscura/medium/spectral_lerp.h"

namespace obscura {

// The first real collision along the ray in [0, t_max] (t in metres), or
// nothing when the ray gets through (probability e^{−τ(0, t_max)}).
// `scratch` avoids allocations in the inner loop; after a collision it holds
// the medium's coefficients at the collision point for lambda's two samples
// and the temperature (Medium::coefficients_of_samples; the other samples
// unspecified).
std::optional<double> sample_free_flight(const Medium& medium, const Ray& ray, double t_max,
                                         const SpectralLerp& lambda, Rng& rng,
                                         MediumPoint& scratch);

// Unbiased estimate of the transmittance e^{−τ(0, t_max)} by residual ratio
// tracking (the majorant pieces' minorants as the control; exact where the
// medium is constant over a piece), with Russian roulette once the estimate
// falls below 0.05.
double estimate_transmittance(const Medium& medium, const Ray& ray, double t_max,
                              const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch);

}  // namespace obscura
