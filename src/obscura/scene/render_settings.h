#pragma once
// How to render a scene: the solver and its accuracy/effort knobs.
#include <cstdint>
#include <string>

namespace obscura {

// Volume photon mapping ("method": "photonmap"; render/photon_map_integrator.h).
struct PhotonMapSettings {
  long long photons_per_node = 200000;  // launched per spectral node
  int k = 50;                           // nearest photons per estimate
  double max_radius_m = 1.0;            // search radius cap
  double radius_mean_free_paths = 0.5;  // … and at most this many local mean free paths 1/σt
  double step_m = 1.0;  // longest marching segment (chosen by measurement: docs/validation.md)
  bool pure = false;    // the paper's form: photons for all in-scattering
  bool camera_sees_sun = true;  // off only where a caller scores the direct beam itself
};

struct RenderSettings {
  // "emission-absorption" (exact, scattering as extinction only),
  // "path-tracer" (unbiased Monte Carlo of the full RTE, with standard errors)
  // or "photonmap" (volume photon mapping: consistent, biased by the density
  // estimate, much faster for multiple scattering).
  std::string method = "emission-absorption";
  // Emission-absorption: 1 = the pixel centre, more = stratified jitter.
  // Path tracer: paths per pixel (each covering every spectral node).
  int samples_per_pixel = 1;
  // Path tracer: when > 0, each pixel takes further rounds of
  // samples_per_pixel paths until the standard error of every band radiance is
  // at most this fraction of its mean, or max_samples_per_pixel is reached.
  double target_relative_stderr = 0.0;
  int max_samples_per_pixel = 4096;
  int spectral_nodes_per_band = 8;   // Gauss–Legendre nodes across each band
  double relative_tolerance = 1e-6;  // emission integral per cell
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all cores
  PhotonMapSettings photon_map;
};

}  // namespace obscura
