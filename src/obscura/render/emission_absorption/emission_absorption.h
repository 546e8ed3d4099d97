#pragma once
// Emission–absorption solution of the radiative transfer equation along a ray
// (docs/physics.md, "The radiative transfer equation", with σs acting only as
// extinction: exact where σs = 0):
//   L = ∫₀^t_max e^{−τ(0,s)} σa(s) B_λ(T(s)) ds + e^{−τ(0,t_max)} L_background.
// The medium is visited segment by segment (one reconstruction cell each);
// inside a segment σa, σs and T are exact cubics in s, so the optical depth
// τ(s) = ∫ σt is integrated in closed form, and the emission integral by
// adaptive Simpson quadrature (Lyness 1969) until its estimated error is below
// the relative tolerance. No fixed step: no feature can be stepped over.
#include <vector>

#include "obscura/core/ray.h"
#include "obscura/medium/medium.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/render_settings.h"

namespace obscura {

struct EmissionAbsorptionStats {
  std::uint64_t segments = 0;         // medium segments (voxel cells) visited
  std::uint64_t integrand_evals = 0;  // evaluations of the emission integrand
};

// Adds to radiance[i] the medium's emitted spectral radiance seen along the
// ray over [0, t_max] at node i (W m⁻² sr⁻¹ µm⁻¹), and multiplies
// transmittance[i] by e^{−τ}. `medium` may be null (nothing happens).
// The adaptive form ("emission_quadrature": "adaptive"): exact cubics,
// emission to the relative tolerance (the validation mode).
void integrate_emission_absorption(const Medium* medium, const Ray& ray, double t_max,
                                   const SpectralNodes& nodes, double relative_tolerance,
                                   double* radiance, double* transmittance,
                                   EmissionAbsorptionStats* stats = nullptr);

// The same with the fixed-order cell quadrature ("emission_quadrature":
// "cell", the default; cell_quadrature.h has its error bound): three points
// per cell, τ exact, no recursion, a bounded cost per cell.
void integrate_emission_cells(const Medium* medium, const Ray& ray, double t_max,
                              const SpectralNodes& nodes, double* radiance, double* transmittance,
                              EmissionAbsorptionStats* stats = nullptr);

// The form `quadrature` names.
void integrate_emission(const Medium* medium, const Ray& ray, double t_max,
                        const SpectralNodes& nodes, EmissionQuadrature quadrature,
                        double relative_tolerance, double* radiance, double* transmittance,
                        EmissionAbsorptionStats* stats = nullptr);

}  // namespace obscura
