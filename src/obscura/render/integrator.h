#pragma once
// What every render method provides (docs/architecture.md, "Integrators").
// The renderer (render/renderer.h) owns the pixel and sample loop: it makes
// each camera ray, finds its first surface once, and asks the integrator for
// the spectral radiance arriving along it at every node of a band. An
// integrator is made for one staged scene (one frame) and the spectral nodes
// of every sensor's bands; whatever it prepares per frame (photon maps, light
// caches) happens when it is made and is shared by all sensors and bands.
//
// Integrators are const once made and called from many threads at once:
// per-thread scratch lives in a RayWorkspace that the renderer asks for once
// per row and reuses for every ray of the row, so that no ray allocates.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "obscura/core/rng.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

// A ray from a sensor and the first surface along it (found once, by the
// renderer, for every method).
struct CameraRay {
  Ray ray;
  bool on_surface = false;
  SurfaceHit hit;  // valid when on_surface
  // Where the ray ends: the surface, else infinity (m along the ray).
  double t_end() const { return on_surface ? hit.t : std::numeric_limits<double>::infinity(); }
};

// The ray and its first surface hit with t > 0.
CameraRay find_camera_ray_hit(const Scene& scene, const Ray& ray);

// The spectral nodes each band of each sensor is rendered at: [sensor][band].
using FrameSpectra = std::vector<std::vector<SpectralNodes>>;

// Nodes for every band of every sensor of the scene: the settings'
// Gauss–Legendre nodes per band (RenderSettings::spectral_nodes), placed among the
// staged medium's spectral samples. Throws InputError for a band with more
// than kMaxSpectralNodes nodes.
FrameSpectra frame_spectra(const Scene& scene);
// The same for one sensor.
std::vector<SpectralNodes> sensor_spectra(const Scene& scene, const Sensor& sensor);

// The distinct wavelengths among a frame's nodes (what per-frame caches are
// kept for: sensors that share a band share them) and, per sensor, band and
// node, the index of its wavelength among them.
struct DistinctNodes {
  std::vector<SpectralNode> nodes;
  std::vector<std::vector<std::vector<int>>> index;  // [sensor][band][node]
};
DistinctNodes distinct_nodes(const FrameSpectra& spectra);
// Per distinct node, the sensors whose bands hold it (indices, ascending).
std::vector<std::vector<int>> sensors_of_nodes(const DistinctNodes& distinct);

// Per-thread scratch of an integrator, and the counters it keeps while it
// works (summed into RenderStats by the renderer).
struct RayWorkspace {
  virtual ~RayWorkspace() = default;
  std::uint64_t segments = 0;         // medium cells visited
  std::uint64_t integrand_evals = 0;  // evaluations of an emission integrand
};

// How far the preparation of a frame is (the photon methods' tracing):
// `done` of `total` photons traced, over all the frame's spectral nodes.
// Called from any thread; an exception it throws stops the preparation.
using PreparationProgress = std::function<void(long long done, long long total)>;

// How a frame's traced photons went, which is what they cost: the photons
// traced (an environment line launches one per piece of it), those with at
// least one real collision in the medium (they meet the smoke), and their
// real collisions (scatterings and absorptions). A walk in a thick cloud
// that scatters without absorbing is long (docs/validation.md).
struct PhotonWalks {
  std::uint64_t photons = 0, colliding = 0, collisions = 0;
  PhotonWalks& operator+=(const PhotonWalks& o) {
    photons += o.photons;
    colliding += o.colliding;
    collisions += o.collisions;
    return *this;
  }
};

// What an integrator spent preparing a frame for one sensor.
struct PreparationStats {
  std::uint64_t photons = 0;       // stored, over all maps
  std::uint64_t photon_bytes = 0;  // their memory
  double seconds = 0;              // wall time of the preparation
  double trace_seconds = 0;        // … of which tracing photons
  double build_seconds = 0;        // … and building search structures
  PhotonWalks walks;               // of the photons traced
};

class Integrator {
 public:
  virtual ~Integrator() = default;

  virtual RenderMethod method() const = 0;
  // Scratch for one thread; reused for every ray it renders.
  virtual std::unique_ptr<RayWorkspace> make_workspace() const = 0;
  // Called once per camera ray before its bands: work that every band of the
  // ray shares (the line-of-sight optical depth, say). Draws no random numbers.
  virtual void begin_ray(const CameraRay& /*ray*/, RayWorkspace& /*workspace*/) const {}
  // The spectral radiance (W m⁻² sr⁻¹ µm⁻¹) arriving along −ray.direction at
  // ray.origin at every node of band `band` of sensor `sensor`, in
  // radiance[node], and the line-of-sight transmittance of the medium up to
  // the first surface at each node, in transmittance[node].
  virtual void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng,
                             RayWorkspace& workspace, double* radiance,
                             double* transmittance) const = 0;
  // The frame's preparation for `sensor` (zero for methods that prepare nothing).
  virtual PreparationStats preparation(int /*sensor*/) const { return {}; }
};

}  // namespace obscura
