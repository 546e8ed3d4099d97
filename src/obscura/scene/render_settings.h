#pragma once
// How to render a scene: the solver and its accuracy/effort knobs.
#include <cstdint>
#include <string>

namespace obscura {

struct RenderSettings {
  // "emission-absorption" (exact, scattering as extinction only) or
  // "path-tracer" (unbiased Monte Carlo of the full RTE, with standard errors).
  std::string method = "emission-absorption";
  // Emission-absorption: 1 = the pixel centre, more = stratified jitter.
  // Path tracer: paths per pixel (each covering every spectral node).
  int samples_per_pixel = 1;
  // Path tracer: when > 0, each pixel takes further rounds of
  // samples_per_pixel paths until the standard error of every band radiance is
  // at most this fraction of its mean, or max_samples_per_pixel is reached.
  double target_relative_stderr = 0.0;
  int max_samples_per_pixel = 4096;
  int spectral_nodes_per_band = 8;  // Gauss–Legendre nodes across each band
  double relative_tolerance = 1e-6;  // emission integral per cell
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all cores
};

}  // namespace obscura
