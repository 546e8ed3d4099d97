#pragma once
// How to render a scene: the method and its accuracy/effort knobs. Every
// setting lives here once: the scene file's "render" object is parsed into
// it, the command line overrides fields of the same struct, and
// check_render_settings holds every range (docs/formats.md, "render").
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "obscura/core/band.h"
#include "obscura/core/error.h"

namespace obscura {

// The render methods (render/integrator_registry.h makes each one's integrator).
enum class RenderMethod {
  kEmissionAbsorption,  // exact, scattering as extinction only
  kPathTracer,          // unbiased Monte Carlo of the full RTE, with standard errors
  kPhotonMap,           // volume photon mapping: consistent, biased by the density estimate
  kRadianceCache,       // photons splatted once per frame into a lattice the camera reads
};
inline constexpr std::array kRenderMethods = {RenderMethod::kEmissionAbsorption,
                                              RenderMethod::kPathTracer, RenderMethod::kPhotonMap,
                                              RenderMethod::kRadianceCache};

// The name a scene file and the command line use ("emission-absorption",
// "path-tracer", "photonmap").
std::string_view render_method_name(RenderMethod method);
// The method of that name; nothing for an unknown name.
std::optional<RenderMethod> parse_render_method(std::string_view name);
// "emission-absorption, path-tracer, photonmap": for error messages.
std::string render_method_names();
// Whether the method solves scattering (every method but emission–absorption).
bool method_scatters(RenderMethod method);
// Whether the method is Monte Carlo: its images carry standard errors and it
// may take samples until a target relative standard error is met.
bool method_is_monte_carlo(RenderMethod method);

// The volumetric path tracer ("path_tracer": {…}; render/path_tracer).
struct PathTracerSettings {
  int russian_roulette_depth = 4;  // bounces before roulette starts
  int max_depth = 100000;          // a safety net; roulette ends paths long before
  // Sample the sky directly at every vertex (combined with the scattering
  // direction by multiple importance sampling), or find it only by escaping
  // paths. Both are unbiased. kAuto samples table skies only: for a uniform
  // blackbody sky the scattering direction is already distributed as well as
  // the sky's, and the extra ratio-tracked shadow ray only adds noise
  // (measured, docs/validation.md: furnace standard error 20× larger).
  enum class SkySampling { kAuto, kAlways, kNever };
  SkySampling sky_next_event = SkySampling::kAuto;
};

// Volume photon mapping ("photon_map": {…}; render/photon_map).
struct PhotonMapSettings {
  long long photons_per_node = 200000;  // launched per spectral node
  int k = 50;                           // nearest photons per estimate
  double max_radius_m = 1.0;            // search radius cap
  double radius_mean_free_paths = 0.5;  // … and at most this many local mean free paths 1/σt
  double step_m = 1.0;  // longest marching segment (chosen by measurement: docs/validation.md)
  bool pure = false;    // the paper's form: photons for all in-scattering
};

// How emission is integrated across a medium cell (every method's emission
// and the radiance cache's in-scattering): "cell", the fixed three-point cell
// quadrature with a documented error bound and a bounded cost per cell
// (render/emission_absorption/cell_quadrature.h), or "adaptive", exact cubics
// with adaptive Simpson to relative_tolerance (the validation mode).
enum class EmissionQuadrature { kCell, kAdaptive };

// The radiance cache ("radiance_cache": {…}; render/radiance_cache).
struct RadianceCacheSettings {
  // Lattice spacing, m; 0: the cloud's voxel size (a grid cloud), else the
  // medium's largest extent / 32.
  double voxel_m = 0.0;
  long long photons_per_node = 1000000;  // launched per spectral node
  // Per band (its name as the sensors give it: a preset or "LO:HI"): the
  // photons launched per spectral node of that band instead, where it needs
  // fewer or more than the others (a band where the smoke scatters little or
  // not at all converges with far fewer: docs/performance.md). A node that
  // two bands share takes the larger count.
  std::map<std::string, long long> photons_by_band;
  // The photons per node of band `band`'s nodes.
  long long photons(const Band& band) const;
  int sh_degree = 2;  // spherical-harmonic degree of the incident radiance, 1–6 (GPU: 1–3)
  // Splatting kernel half-width, in lattice spacings: a tent of that
  // half-width per axis (1: each photon to the 8 nodes around it).
  int kernel_radius_nodes = 1;
  // Lattice and photons periodic in x and y with this period, m (0: off): a
  // laterally infinite, laterally homogeneous slab (validate slab).
  double lateral_period_m = 0.0;
  // "estimate": "tracks" splats every photon flight along its length (the
  // track-length estimate, where the lattice lies on a grid cloud; a wider
  // kernel filters its sums, widen_splat in render/radiance_cache/flight_splat.h),
  // "collisions" only the scattering events.
  bool track_length = true;
  // "sensor_peaks": the phase function's forward peak beyond the harmonics
  // is splatted towards each narrow sensor's viewing direction (its image's
  // half-diagonal ≤ 5°, sensors within 1° of each other sharing one, as many
  // directions as a light record's padding holds: one at SH degree 0 or 2,
  // two at 1 or 3) with the track-length estimate, so that a cloud seen
  // against the sun is not dimmed or brightened by the truncation
  // (render/radiance_cache/radiance_cache.h).
  bool sensor_peaks = true;
};

// Where the camera march runs ("device": "cpu" | "gpu"; docs/gpu.md). The
// GPU (a CUDA build, gpu/) marches emission–absorption and the radiance cache
// over a cloud that is one voxel grid; everything else runs on the CPU.
enum class RenderDevice { kCpu, kGpu };

// "cpu" or "gpu"; nothing for another name.
std::optional<RenderDevice> parse_render_device(std::string_view name);
std::string_view render_device_name(RenderDevice device);

struct RenderSettings {
  RenderMethod method = RenderMethod::kEmissionAbsorption;
  // Emission-absorption: 1 = the pixel centre, more = stratified jitter.
  // Monte Carlo methods: paths per pixel (each covering every spectral node).
  int samples_per_pixel = 1;
  // Deterministic methods (emission-absorption, radiance-cache) with
  // samples_per_pixel > 1: when > 0, every pixel first takes one sample at
  // its centre, and only a pixel whose centre differs from a neighbour's (any
  // of its 8) by more than this fraction of the larger band radiance, or by
  // more than this in transmittance, in any band, takes the samples_per_pixel
  // stratified samples (the same ones as without it); the others keep their
  // centre. 0: every pixel takes samples_per_pixel (render/adaptive_samples.h).
  double adaptive_threshold = 0.0;
  // Monte Carlo methods: when > 0, each pixel takes further rounds of
  // samples_per_pixel paths until the standard error of every band radiance is
  // at most this fraction of its mean, or max_samples_per_pixel is reached.
  double target_relative_stderr = 0.0;
  int max_samples_per_pixel = 4096;
  int spectral_nodes_per_band = 8;  // Gauss–Legendre nodes across each band…
  // …but these bands, by their name in the sensors ("laser1064", "8:12"):
  // a narrow band (a laser line) needs fewer for the same spectral accuracy
  // (the photon methods launch photons per node, so there fewer nodes also
  // mean fewer photons for the band).
  std::map<std::string, int> spectral_nodes_by_band;
  // The nodes band `band` takes.
  int spectral_nodes(const Band& band) const;
  EmissionQuadrature emission_quadrature = EmissionQuadrature::kCell;
  double relative_tolerance = 1e-6;  // the adaptive emission integral per cell
  // Camera rays that escape inside the sun's disc see the sun. Off where a
  // caller scores the unscattered sunlight itself (validate slab: T_direct).
  bool camera_sees_sun = true;
  std::uint64_t seed = 1;                    // every random stream derives from it
  int threads = 0;                           // 0: all cores; images do not depend on it
  RenderDevice device = RenderDevice::kCpu;  // where the camera march runs
  PathTracerSettings path_tracer;
  PhotonMapSettings photon_map;
  RadianceCacheSettings radiance_cache;
};

// How a setting is named in an error: `key` is its path below the render
// object ("samples_per_pixel", "photon_map/k"). The scene loader names the
// file and JSON path; the command line names its option.
using SettingError = std::function<InputError(std::string_view key, std::string_view what)>;

// Throws the InputError `error` makes for the first setting out of its range
// or not meant for the method (target_relative_stderr with
// emission–absorption).
void check_render_settings(const RenderSettings& settings, const SettingError& error);

class JsonObject;
// The "render" object of a scene file over `defaults`: unknown keys, wrong
// types and out-of-range values are InputErrors naming the JSON path.
RenderSettings parse_render_settings(JsonObject& render, RenderSettings defaults = {});

}  // namespace obscura
