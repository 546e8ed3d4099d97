#include "obscura/scene/render_settings.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "obscura/io/json_reader.h"

namespace obscura {
namespace {

struct MethodInfo {
  RenderMethod method;
  std::string_view name;
  bool scatters;
  bool monte_carlo;
};

constexpr std::array<MethodInfo, kRenderMethods.size()> kMethodInfo = {{
    {RenderMethod::kEmissionAbsorption, "emission-absorption", false, false},
    {RenderMethod::kPathTracer, "path-tracer", true, true},
    {RenderMethod::kPhotonMap, "photonmap", true, true},
    {RenderMethod::kRadianceCache, "radiance-cache", true, false},
}};

const MethodInfo& info(RenderMethod method) {
  for (const MethodInfo& m : kMethodInfo)
    if (m.method == method) return m;
  throw Error("render: a method without an entry in kMethodInfo");
}

// A JSON integer narrowed to int; values beyond int's range saturate, so the
// range check that follows reports them rather than a wrapped value.
int saturate_int(long long v) {
  constexpr long long lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
  return static_cast<int>(v < lo ? lo : v > hi ? hi : v);
}

// A count for every band, or {band: count, "*": count for the others} (the
// atmosphere's extinction_per_km form): into `all` and `by_band`, each count
// through `narrow` (saturate_int for an int).
template <class Count, class Narrow>
void parse_count_by_band(JsonObject& o, const std::string& key, Count& all,
                         std::map<std::string, Count>& by_band, Narrow narrow) {
  if (o.has(key) && o.raw(key).is_object()) {
    JsonObject counts = o.object(key);
    for (const auto& [band, value] : o.raw(key).items()) {
      const Count count = narrow(counts.integer(band));
      if (band == "*")
        all = count;
      else
        by_band[band] = count;
    }
    counts.finish();
  } else {
    all = narrow(o.integer_or(key, all));
  }
}

PathTracerSettings::SkySampling parse_sky_sampling(JsonObject& o, const std::string& key,
                                                   PathTracerSettings::SkySampling fallback) {
  using S = PathTracerSettings::SkySampling;
  if (!o.has(key)) return fallback;
  const std::string v = o.string(key);
  if (v == "auto") return S::kAuto;
  if (v == "always") return S::kAlways;
  if (v == "never") return S::kNever;
  throw o.error(key, fmt::format("'{}' is not one of auto, always, never", v));
}

void parse_path_tracer(JsonObject& o, PathTracerSettings& p) {
  p.russian_roulette_depth =
      saturate_int(o.integer_or("russian_roulette_depth", p.russian_roulette_depth));
  p.max_depth = saturate_int(o.integer_or("max_depth", p.max_depth));
  p.sky_next_event = parse_sky_sampling(o, "sky_next_event", p.sky_next_event);
  o.finish();
}

void parse_photon_map(JsonObject& o, PhotonMapSettings& p) {
  p.photons_per_node = o.integer_or("photons", p.photons_per_node);
  p.k = saturate_int(o.integer_or("k", p.k));
  p.max_radius_m = o.number_or("max_radius_m", p.max_radius_m);
  p.step_m = o.number_or("step_m", p.step_m);
  p.radius_mean_free_paths = o.number_or("radius_mean_free_paths", p.radius_mean_free_paths);
  const std::string form = o.string_or("form", p.pure ? "pure" : "hybrid");
  if (form != "hybrid" && form != "pure")
    throw o.error("form",
                  "must be \"hybrid\" (shadow rays for single scattering) or \"pure\" "
                  "(photons for all scattering, the source paper's form)");
  p.pure = form == "pure";
  o.finish();
}

void parse_radiance_cache(JsonObject& o, RadianceCacheSettings& c) {
  c.voxel_m = o.number_or("voxel_m", c.voxel_m);
  parse_count_by_band(o, "photons", c.photons_per_node, c.photons_by_band,
                      [](long long v) { return v; });
  c.sh_degree = saturate_int(o.integer_or("sh_degree", c.sh_degree));
  c.kernel_radius_nodes = saturate_int(o.integer_or("kernel_radius_nodes", c.kernel_radius_nodes));
  c.lateral_period_m = o.number_or("lateral_period_m", c.lateral_period_m);
  const std::string estimate = o.string_or("estimate", c.track_length ? "tracks" : "collisions");
  if (estimate != "tracks" && estimate != "collisions")
    throw o.error("estimate",
                  "must be \"tracks\" (every photon flight splatted along its length, where "
                  "the lattice lies on a grid cloud) or \"collisions\" (at scattering events)");
  c.track_length = estimate == "tracks";
  c.sensor_peaks = o.boolean_or("sensor_peaks", c.sensor_peaks);
  o.finish();
}

}  // namespace

std::string_view render_method_name(RenderMethod method) { return info(method).name; }

std::optional<RenderMethod> parse_render_method(std::string_view name) {
  for (const MethodInfo& m : kMethodInfo)
    if (m.name == name) return m.method;
  return std::nullopt;
}

std::string render_method_names() {
  std::string names;
  for (const MethodInfo& m : kMethodInfo)
    names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

std::optional<RenderDevice> parse_render_device(std::string_view name) {
  if (name == "cpu") return RenderDevice::kCpu;
  if (name == "gpu") return RenderDevice::kGpu;
  return std::nullopt;
}

std::string_view render_device_name(RenderDevice device) {
  return device == RenderDevice::kGpu ? "gpu" : "cpu";
}

namespace {

// A count set per band (parse_count_by_band): band's own, else `all`.
template <class Count>
Count count_of_band(const std::map<std::string, Count>& by_band, Count all, const Band& band) {
  const auto it = by_band.find(band.name());
  return it == by_band.end() ? all : it->second;
}

}  // namespace

int RenderSettings::spectral_nodes(const Band& band) const {
  return count_of_band(spectral_nodes_by_band, spectral_nodes_per_band, band);
}

long long RadianceCacheSettings::photons(const Band& band) const {
  return count_of_band(photons_by_band, photons_per_node, band);
}

bool method_scatters(RenderMethod method) { return info(method).scatters; }
bool method_is_monte_carlo(RenderMethod method) { return info(method).monte_carlo; }

void check_render_settings(const RenderSettings& s, const SettingError& error) {
  auto require = [&](bool ok, std::string_view key, std::string_view what) {
    if (!ok) throw error(key, what);
  };
  require(s.samples_per_pixel >= 1 && s.samples_per_pixel <= 65536, "samples_per_pixel",
          "must lie in [1, 65536]");
  require(s.target_relative_stderr >= 0 && s.target_relative_stderr < 1, "target_relative_stderr",
          "must lie in [0, 1) (0: a fixed sample count)");
  require(s.max_samples_per_pixel >= 1 && s.max_samples_per_pixel <= 1048576,
          "max_samples_per_pixel", "must lie in [1, 1048576]");
  require(s.spectral_nodes_per_band >= 1 && s.spectral_nodes_per_band <= 64,
          "spectral_nodes_per_band", "must lie in [1, 64]");
  for (const auto& [band, nodes] : s.spectral_nodes_by_band)
    require(nodes >= 1 && nodes <= 64, "spectral_nodes_per_band/" + band, "must lie in [1, 64]");
  require(s.relative_tolerance >= 1e-12 && s.relative_tolerance <= 0.1, "relative_tolerance",
          "must lie in [1e-12, 0.1]");
  require(s.threads >= 0 && s.threads <= 4096, "threads", "must lie in [0, 4096] (0: all cores)");
  require(s.adaptive_threshold >= 0 && s.adaptive_threshold < 1, "adaptive_threshold",
          "must lie in [0, 1) (0: every pixel takes samples_per_pixel samples)");
  require(s.adaptive_threshold == 0 || !method_is_monte_carlo(s.method), "adaptive_threshold",
          fmt::format("applies to the deterministic methods only (\"emission-absorption\", "
                      "\"radiance-cache\"; \"{}\" takes target_relative_stderr)",
                      render_method_name(s.method)));
  require(s.adaptive_threshold == 0 || s.samples_per_pixel > 1, "adaptive_threshold",
          "refines pixels to samples_per_pixel samples, which is 1 here: set samples_per_pixel "
          "above 1 or leave adaptive_threshold out");
  require(s.target_relative_stderr == 0 || method_is_monte_carlo(s.method),
          "target_relative_stderr",
          "applies to the Monte Carlo methods only (set /render/method to \"path-tracer\" or "
          "\"photonmap\")");

  require(s.device == RenderDevice::kCpu || s.method == RenderMethod::kEmissionAbsorption ||
              s.method == RenderMethod::kRadianceCache,
          "device",
          fmt::format("\"gpu\" renders \"method\": \"emission-absorption\" and "
                      "\"radiance-cache\" only (not \"{}\"): set \"device\": \"cpu\" or "
                      "one of those methods (docs/gpu.md)",
                      render_method_name(s.method)));
  require(s.device == RenderDevice::kCpu || s.emission_quadrature == EmissionQuadrature::kCell,
          "device",
          "\"gpu\" integrates with \"emission_quadrature\": \"cell\" only: set "
          "\"device\": \"cpu\" for the adaptive quadrature (docs/gpu.md)");
  require(s.device == RenderDevice::kCpu || s.method != RenderMethod::kRadianceCache ||
              s.radiance_cache.sh_degree <= 3,
          "radiance_cache/sh_degree",
          "\"gpu\" holds degrees 1 to 3: set \"device\": \"cpu\" for degrees 4 to 6 "
          "(docs/gpu.md)");

  const PathTracerSettings& pt = s.path_tracer;
  require(pt.russian_roulette_depth >= 1 && pt.russian_roulette_depth <= 1000,
          "path_tracer/russian_roulette_depth", "must lie in [1, 1000] bounces");
  require(pt.max_depth >= 1 && pt.max_depth <= 100000000, "path_tracer/max_depth",
          "must lie in [1, 1e8] bounces");

  const PhotonMapSettings& pm = s.photon_map;
  require(pm.photons_per_node >= 1 && pm.photons_per_node <= 2000000000LL, "photon_map/photons",
          "must lie in [1, 2e9] (photons launched per spectral node)");
  require(pm.k >= 1 && pm.k <= 4096, "photon_map/k", "must lie in [1, 4096]");
  auto positive = [&](double v, std::string_view key) {
    require(v > 0 && std::isfinite(v), key, fmt::format("must be > 0 (got {})", v));
  };
  positive(pm.max_radius_m, "photon_map/max_radius_m");
  positive(pm.step_m, "photon_map/step_m");
  positive(pm.radius_mean_free_paths, "photon_map/radius_mean_free_paths");

  const RadianceCacheSettings& rc = s.radiance_cache;
  require(rc.voxel_m >= 0 && std::isfinite(rc.voxel_m), "radiance_cache/voxel_m",
          "must be >= 0 m (0: the cloud's voxel size)");
  require(rc.photons_per_node >= 1 && rc.photons_per_node <= 2000000000LL, "radiance_cache/photons",
          "must lie in [1, 2e9] (photons launched per spectral node)");
  for (const auto& [band, count] : rc.photons_by_band)
    require(count >= 1 && count <= 2000000000LL, "radiance_cache/photons/" + band,
            "must lie in [1, 2e9] (photons launched per spectral node of the band)");
  // 6: kMaxShDegree (render/radiance_cache/spherical_harmonics.h); a CUDA
  // device's kernels hold degrees up to 3 (kMaxDeviceShDegree).
  require(rc.sh_degree >= 1 && rc.sh_degree <= 6, "radiance_cache/sh_degree", "must lie in [1, 6]");
  require(rc.kernel_radius_nodes >= 1 && rc.kernel_radius_nodes <= 4,
          "radiance_cache/kernel_radius_nodes", "must lie in [1, 4] lattice spacings");
  require(rc.lateral_period_m >= 0 && std::isfinite(rc.lateral_period_m),
          "radiance_cache/lateral_period_m", "must be >= 0 m (0: not periodic)");
}

RenderSettings parse_render_settings(JsonObject& r, RenderSettings s) {
  if (r.has("method")) {
    const std::string name = r.string("method");
    const auto method = parse_render_method(name);
    if (!method)
      throw r.error("method", fmt::format("unknown method '{}' (available: {})", name,
                                          render_method_names()));
    s.method = *method;
  }
  // A method's own settings are accepted only with that method: anything else
  // is a scene that does not do what its author thinks.
  auto method_object = [&](const char* key, RenderMethod method) {
    auto o = r.optional_object(key);
    if (o && s.method != method)
      throw r.error(key,
                    fmt::format("applies to \"method\": \"{}\" only", render_method_name(method)));
    return o;
  };
  if (auto pt = method_object("path_tracer", RenderMethod::kPathTracer))
    parse_path_tracer(*pt, s.path_tracer);
  if (auto pm = method_object("photon_map", RenderMethod::kPhotonMap))
    parse_photon_map(*pm, s.photon_map);
  if (auto rc = method_object("radiance_cache", RenderMethod::kRadianceCache))
    parse_radiance_cache(*rc, s.radiance_cache);
  s.samples_per_pixel = saturate_int(r.integer_or("samples_per_pixel", s.samples_per_pixel));
  s.adaptive_threshold = r.number_or("adaptive_threshold", s.adaptive_threshold);
  s.target_relative_stderr = r.number_or("target_relative_stderr", s.target_relative_stderr);
  s.max_samples_per_pixel =
      saturate_int(r.integer_or("max_samples_per_pixel", s.max_samples_per_pixel));
  parse_count_by_band(r, "spectral_nodes_per_band", s.spectral_nodes_per_band,
                      s.spectral_nodes_by_band, saturate_int);
  if (r.has("emission_quadrature")) {
    const std::string q = r.string("emission_quadrature");
    if (q != "cell" && q != "adaptive")
      throw r.error("emission_quadrature",
                    fmt::format("'{}' is not \"cell\" (fixed three-point quadrature per cell) or "
                                "\"adaptive\" (to relative_tolerance)",
                                q));
    s.emission_quadrature = q == "cell" ? EmissionQuadrature::kCell : EmissionQuadrature::kAdaptive;
  }
  s.relative_tolerance = r.number_or("relative_tolerance", s.relative_tolerance);
  s.camera_sees_sun = r.boolean_or("camera_sees_sun", s.camera_sees_sun);
  const long long seed = r.integer_or("seed", static_cast<long long>(s.seed));
  if (seed < 0) throw r.error("seed", "must be >= 0");
  s.seed = static_cast<std::uint64_t>(seed);
  s.threads = saturate_int(r.integer_or("threads", s.threads));
  if (r.has("device")) {
    const std::string name = r.string("device");
    const auto device = parse_render_device(name);
    if (!device) throw r.error("device", fmt::format("'{}' is not \"cpu\" or \"gpu\"", name));
    s.device = *device;
  }
  r.finish();
  check_render_settings(s, [&](std::string_view key, std::string_view what) {
    return InputError(r.file(), r.path() + "/" + std::string(key), std::string(what));
  });
  return s;
}

}  // namespace obscura
