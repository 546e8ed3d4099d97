#pragma once
// What a render produces for one sensor: per band, the radiance image
// (W m⁻² sr⁻¹), the line-of-sight transmittance of the medium up to the first
// surface (response-weighted over the band, dimensionless), the apparent
// temperature (K, the blackbody temperature with the same band radiance) and,
// for Monte Carlo methods, the radiance's standard error; the samples each
// pixel took; and what the render cost. The film is the layer between the
// renderer that fills it and the analysis and reports that read it
// (docs/architecture.md).
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/core/band.h"

namespace obscura {

struct BandImage {
  Band band;
  std::vector<float> radiance;              // W m⁻² sr⁻¹
  std::vector<float> transmittance;         // 1
  std::vector<float> apparent_temperature;  // K
  // Standard error of the radiance (W m⁻² sr⁻¹): Monte Carlo methods only, else empty.
  std::vector<float> radiance_stderr;
};

struct RenderStats {
  std::uint64_t rays = 0;
  std::uint64_t segments = 0;  // medium cells visited, summed over bands
  std::uint64_t integrand_evals = 0;
  double seconds = 0;
  // Photon mapping: photons stored over all maps, their memory, pass-1 time.
  std::uint64_t photons = 0;
  std::uint64_t photon_bytes = 0;
  double photon_seconds = 0;
  double photon_trace_seconds = 0;  // … of which tracing photons
  double photon_build_seconds = 0;  // … and building the kd-trees
  // Photons traced, those with a real collision in the medium, and their
  // real collisions: where the photons' time goes.
  std::uint64_t photons_traced = 0, photons_colliding = 0, photon_collisions = 0;
};

// Pixels are row-major, top row first: pixel (x, y) is at y * width + x.
struct SensorImage {
  std::string sensor;
  int width = 0, height = 0;
  std::vector<BandImage> bands;
  // Samples taken per pixel (row-major): samples_per_pixel, or more with a
  // target relative standard error (path tracer).
  std::vector<std::uint32_t> samples_per_pixel;
  RenderStats stats;
};

}  // namespace obscura
