#pragma once
// The light in a cloud, computed once per frame and read by every camera ray
// (the source paper's "photon splatting"; docs/physics.md, "The radiance
// cache"). On a CacheLattice over the medium it stores:
//  * per node and medium spectral sample, the optical depth τ_sun towards the
//    sun (exact, through every medium) and whether a surface shades the node
//    from the sun; the sun's single scattering at a point is then
//    σs p_HG(ω_sun·ω) E_sun e^{−τ_sun}, the phase function exact for each
//    camera direction;
//  * per node and spectral node, everything else that is scattered (multiple
//    scattering, the sky and surfaces' light, scattered volume emission) as
//    spherical-harmonic coefficients c_lm = ∫ Y_lm L_in dω of the incident
//    radiance, from the photons of pass 1 (photon_tracing.h) splatted with a
//    tent kernel K of half-width r lattice spacings:
//      c_lm(n) = Σ_p ΔΦ_p Y_lm(ω_p) K(x_p − x_n) / ∫ K(x − x_n) σs(x) dV,
//    the denominator because photons are stored where they scatter, at a rate
//    σs L_in, so that the part of a kernel outside the cloud does not dilute
//    the estimate near its edge.
// Deterministic for a given seed whatever the thread count.
#include <cstddef>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"
#include "obscura/render/radiance_cache/cache_lattice.h"
#include "obscura/render/radiance_cache/spherical_harmonics.h"

namespace obscura {

class RadianceCache {
 public:
  // The cache of the staged scene for `nodes` (each a distinct wavelength),
  // with scene.settings.radiance_cache, seed and threads. The scene needs a
  // medium.
  // `processes` share the photon tracing (render/photon_map/photon_tracing.h).
  RadianceCache(const Scene& scene, const std::vector<SpectralNode>& nodes,
                const ProcessGroup& processes = single_process());

  const CacheLattice& lattice() const { return lattice_; }
  int sh_degree() const { return sh_degree_; }
  int sh_count() const { return sh_count_; }
  int spectral_count() const { return spectral_count_; }  // medium samples
  bool has_sun() const { return has_sun_; }

  // Per slot: τ_sun for each medium sample, then the sun visibility (0 or 1).
  const float* sun(std::size_t slot) const {
    return sun_.data() + slot * static_cast<std::size_t>(spectral_count_ + 1);
  }
  // Per slot: the sh_count() coefficients of node `node`'s incident radiance
  // (W m⁻² sr⁻¹ µm⁻¹ × sr).
  const float* radiance(int node, std::size_t slot) const {
    return radiance_[static_cast<std::size_t>(node)].data() + slot * sh_count_;
  }

  // What building it cost.
  std::uint64_t photons_stored() const { return photons_stored_; }
  std::size_t memory_bytes() const;
  double seconds = 0, sun_seconds = 0, photon_seconds = 0, splat_seconds = 0;

 private:
  void compute_sun(const Scene& scene);
  // ∫ K(x − x_n) σs(x) dV per slot and medium sample: the splats' denominator.
  std::vector<float> kernel_scattering(const Scene& scene) const;
  void splat(const Scene& scene, const SpectralNode& node, int index,
             const std::vector<float>& kernel_sigma_s);

  CacheLattice lattice_;
  const ProcessGroup* processes_;
  int sh_degree_ = 2, sh_count_ = 9, spectral_count_ = 1;
  bool has_sun_ = false;
  std::vector<float> sun_;
  std::vector<std::vector<float>> radiance_;
  std::uint64_t photons_stored_ = 0;
};

}  // namespace obscura
