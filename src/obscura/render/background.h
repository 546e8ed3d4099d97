#pragma once
// What a camera ray finds behind the cloud, without light transport through
// the cloud other than its exact attenuation (docs/physics.md, "Surfaces and
// sky"): the emission–absorption method's whole background and the radiance
// cache's.
//
//  * on a surface: its emission ε B(T), the fraction ρ = 1 − ε of the sky it
//    faces that it reflects (the sky's cosine-weighted mean over its
//    hemisphere), and the sun it reflects, ρ/π E_sun cos θ_sun e^{−τ_sun},
//    with the exact optical depth τ_sun of every medium between the point and
//    the sun (zero when another surface shades it or it faces away);
//  * else the sky, and the sun's disc when the settings let cameras see it.
// The cloud's own light on surfaces and its effect on the sky's part are left
// out: the Monte Carlo methods have them.
#include <vector>

#include "obscura/render/integrator.h"

namespace obscura {

// Per-thread scratch: the optical depth to the sun per medium sample.
struct BackgroundScratch {
  std::vector<double> tau_sun;
};

// The background radiance (W m⁻² sr⁻¹ µm⁻¹) of `camera` at every node of
// `nodes`, into out[node]. Deterministic.
void background_radiance(const Scene& scene, const CameraRay& camera, const SpectralNodes& nodes,
                         BackgroundScratch& scratch, double* out);

}  // namespace obscura
