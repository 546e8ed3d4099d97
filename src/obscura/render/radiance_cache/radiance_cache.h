#pragma once
// The light in a cloud, computed once per frame and read by every camera ray
// (the source paper's "photon splatting"; docs/physics.md, "The radiance
// cache"). On a NodeLattice over the medium it stores, per node and spectral
// node, in the records of a LatticeVolume (render/lattice/lattice_volume.h):
//  * the optical depth τ_sun towards the sun (exact, through every medium)
//    and whether a surface shades the node from the sun (V_sun, 0 or 1); the
//    sun's single scattering at a point is then
//    σs p_HG(ω_sun·ω) E_sun V_sun e^{−τ_sun}, the phase function exact for
//    each camera direction (a rim node outside the grid's box holds
//    2 τ(face) − τ(inner neighbour): lattice_view.h, rim_face);
//  * with the track-length splat, for the viewing directions ω_v of narrow
//    sensors (as many as a record's padding holds: one or two), what the
//    truncated harmonics leave out of the phase function towards ω_v,
//    splatted the same way:
//      J_peak,v(n) = Σ_p ΔΦ_p q(ω_p·ω_v; g) K / ∫ K σs dV,
//    q = p_HG − its expansion to the cache's degree (cache_source.h); a ray
//    of that sensor adds it to J. Off the sensor's axis it is read as on it,
//    hence only for sensors a few degrees wide;
//  * everything else that is scattered (multiple
//    scattering, the sky and surfaces' light, scattered volume emission) as
//    spherical-harmonic coefficients c_lm = ∫ Y_lm L_in dω of the incident
//    radiance, from the photons of pass 1 (photon_tracing.h) splatted with a
//    tent kernel K of half-width r lattice spacings:
//      c_lm(n) = Σ_p ΔΦ_p Y_lm(ω_p) K(x_p − x_n) / ∫ K(x − x_n) σs(x) dV,
//    the denominator because photons are stored where they scatter, at a rate
//    σs L_in, so that the part of a kernel outside the cloud does not dilute
//    the estimate near its edge; each estimate is then moved from its
//    kernel's σs-weighted centroid to its node (estimates_at_nodes.h).
// When the lattice is laid on the cloud's own voxel grid the records also
// hold the medium, and the camera march reads nothing else
// (render/lattice/lattice_march.h). Deterministic for a given seed whatever
// the thread count.
#include <cstddef>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/lattice/node_lattice.h"
#include "obscura/render/photon_map/photon_tracing.h"
#include "obscura/render/radiance_cache/ground_light.h"
#include "obscura/render/radiance_cache/light_region.h"
#include "obscura/render/radiance_cache/spherical_harmonics.h"

namespace obscura {

class RadianceCache {
 public:
  // The cache of the staged scene for `nodes` (each a distinct wavelength),
  // with scene.settings.radiance_cache, seed and threads. The scene needs a
  // medium.
  // `processes` share the photon tracing (render/photon_map/photon_tracing.h).
  // `sun_depths`: who computes τ_sun, this constructor on the CPU or the
  // caller afterwards (the GPU's sun kernel, gpu/sun_depth_job.h), which finds
  // the channel zero and V_sun filled in.
  enum class SunDepths { kHere, kByCaller };
  // `node_sensors`: per node (in the order given), the indices of the
  // scene's sensors whose camera rays alone will read it; the light (the
  // track-length splat and the sun's depths) is then made only in the box
  // around what they see (light_region.h: the same bits there, zero
  // elsewhere). Empty: everywhere, for rays in any direction.
  // `node_photons`: per node, the photons launched for its light (empty:
  // settings' photons_per_node for every node; photons_of_nodes).
  // `progress`: the photons traced so far by this process, of all nodes'.
  RadianceCache(const Scene& scene, const std::vector<SpectralNode>& nodes,
                const ProcessGroup& processes = single_process(),
                SunDepths sun_depths = SunDepths::kHere,
                const std::vector<std::vector<int>>& node_sensors = {},
                const std::vector<long long>& node_photons = {},
                const PreparationProgress& progress = {});

  // Sensors whose image's half-diagonal is at most this get the phase
  // function's forward peak beyond the harmonics (sensor_peaks).
  static constexpr double kMaxPeakHalfAngleDeg = 5.0;

  const NodeLattice& lattice() const { return lattice_; }
  // The light channel (from record::kTauSun, CacheLight::peak) holding the
  // forward peak towards sensor `sensor`'s view, −1 where it has none.
  int peak_channel(int sensor) const {
    return sensor < static_cast<int>(sensor_peak_.size()) ? sensor_peak_[sensor] : -1;
  }
  // The cells whose light is made for spectral node `node` (all_cells
  // without node_sensors).
  const CellBox& light_cells(int node) const {
    return light_cells_[static_cast<std::size_t>(node)];
  }
  int sh_degree() const { return sh_degree_; }
  int sh_count() const { return sh_count_; }
  int spectral_count() const { return spectral_count_; }  // medium samples
  bool has_sun() const { return has_sun_; }

  // Per spectral node (in the order given) and slot, a record of
  // volume().stride() floats: the medium's channels when volume().has_medium(),
  // then τ_sun, V_sun and the sh_count() coefficients c_lm of the incident
  // radiance (W m⁻² sr⁻¹ µm⁻¹ × sr), from record::kTauSun on.
  const LatticeVolume& volume() const { return volume_; }
  // The cloud's light on the ground at spectral node `node` (its index in
  // the order given; ground_light.h): empty without terrain surfaces.
  const GroundLight& ground(int node) const { return ground_[static_cast<std::size_t>(node)]; }

  // What building it cost.
  std::uint64_t photons_stored() const { return photons_stored_; }
  // The photons' walks over every spectral node (photon_tracing.h).
  const PhotonWalks& photon_walks() const { return walks_; }
  std::size_t memory_bytes() const;
  double seconds = 0, sun_seconds = 0, photon_seconds = 0, splat_seconds = 0;

 private:
  void compute_sun(const Scene& scene, const std::vector<SpectralNode>& nodes);
  void choose_light_cells(const Scene& scene, std::size_t nodes,
                          const std::vector<std::vector<int>>& node_sensors);
  void choose_peak_views(const Scene& scene);
  // Per slot and medium sample, ∫ K(x − x_n) σs(x) dV (the splats'
  // denominator) and its first moments ∫ K σs (x − x_n) dV along the
  // lattice's axes, in node units: kKernelMoments values.
  static constexpr int kKernelMoments = 4;
  std::vector<float> kernel_scattering(const Scene& scene) const;
  void splat(const Scene& scene, const SpectralNode& node, int index,
             const std::vector<float>& kernel_moments, PhotonTracingProgress& progress);
  // Whether the medium scatters anywhere at spectral node `index` (σs ≠ 0 in
  // some record; true where the records do not hold the medium).
  bool node_scatters(int index) const;
  // Spectral node `index`'s light channels from the splat's `sum`
  // (per_slot values per slot): each divided by ∫ K σs dV and moved from its
  // kernel's σs-weighted centroid to its node.
  void normalise(int index, const SpectralLerp& lerp, const std::vector<float>& kernel_moments,
                 const std::vector<double>& sum, std::size_t per_slot, int kernel_radius,
                 int threads);
  // Whether the splats take the photons' flights (the track-length
  // estimate, flight_splat.h) rather than their collisions: where the
  // records hold the medium (a wider kernel than one spacing by widen_splat).
  bool splats_flights(const RadianceCacheSettings& settings) const {
    return settings.track_length && volume_.has_medium();
  }

  NodeLattice lattice_;
  const ProcessGroup* processes_;
  int sh_degree_ = 2, sh_count_ = 9, spectral_count_ = 1;
  bool has_sun_ = false;
  // The directions light leaves towards the sensors with a forward peak
  // (unit, world), and per sensor its peak_channel.
  std::vector<Vec3> peak_views_;
  std::vector<int> sensor_peak_;
  SunDepths sun_depths_ = SunDepths::kHere;
  LatticeVolume volume_;
  std::vector<GroundLight> ground_;      // per spectral node
  std::vector<CellBox> light_cells_;     // per spectral node
  CellBox sun_cells_;                    // their union's bounds
  bool light_in_view_ = false;           // whether they are boxes around sensors' views
  std::vector<long long> node_photons_;  // per spectral node, launched
  std::uint64_t photons_stored_ = 0;
  PhotonWalks walks_;
};

// Adds to `behind[j]` (a surface's radiance seen along camera ray `camera`,
// render/background.h) the cloud's light on the ground, ρ ΔE n_z / π
// (ground_light.h), when the ray ends on ground the cache's maps cover;
// `record[j]` is node j's spectral node in the cache.
void add_ground_light(const Scene& scene, const RadianceCache& cache, const CameraRay& camera,
                      const SpectralNodes& nodes, const int* record, double* behind);

// Per distinct node of a frame, the photons its light is made from: the
// count /render/radiance_cache/photons gives the bands that hold it (the
// largest where several do), else photons_per_node.
std::vector<long long> photons_of_nodes(const Scene& scene, const DistinctNodes& distinct);

}  // namespace obscura
