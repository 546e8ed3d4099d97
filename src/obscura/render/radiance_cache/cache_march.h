#pragma once
// The radiance cache's camera march (docs/physics.md, "The radiance cache"):
// in every medium cell the emission σa B(T) and the scattered light σs J are
// integrated together with the cell quadrature and the exact transmittance,
//   J(x, ω) = E_sun p_HG(ω_sun·ω) V_sun e^{−τ_sun(x)} + Σ_l g^l Σ_m Y_lm(ω) c_lm(x),
// τ_sun, V_sun and c_lm trilinear from the cache: no shadow ray, no
// environment ray, no nearest-neighbour query. Two ways to the same sum:
//  * march_cache_lattice: over the cache's records alone, which hold the
//    medium too when the lattice is laid on the cloud's own voxel grid
//    (RadianceCache::volume().has_medium(); render/lattice/lattice_march.h);
//  * march_cache_medium: over the medium's own cells (Medium::march_cells,
//    any medium), reading the light from the records at each point.
// Both take radiance[j] from 0, transmittance[j] and attenuation[j] from 1 to
// the ray's radiance, the line's exact e^{−τ} and what the radiance behind
// the medium is seen through (e^{−∫(σt − f σs)} with delta-M,
// cache_source.h, else the transmittance) for the nodes of one band, whose
// records are cache.volume().records(record[j]), and return the cells
// visited.
// `peak_channel`: the ray's sensor's forward peak (RadianceCache::peak_channel;
// only the lattice's records hold one); a ray without one takes delta-M.
#include <cstdint>

#include "obscura/render/integrator.h"
#include "obscura/render/radiance_cache/radiance_cache.h"

namespace obscura {

std::uint64_t march_cache_lattice(const Scene& scene, const RadianceCache& cache,
                                  const CameraRay& camera, const SpectralNodes& nodes,
                                  const int* record, int peak_channel, double* radiance,
                                  double* transmittance, double* attenuation);

std::uint64_t march_cache_medium(const Scene& scene, const RadianceCache& cache,
                                 const CameraRay& camera, const SpectralNodes& nodes,
                                 const int* record, double* radiance, double* transmittance,
                                 double* attenuation);

}  // namespace obscura
