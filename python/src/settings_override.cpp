#include "settings_override.h"

#include <cmath>

#include "obscura/core/error.h"

namespace obscura::python {

ScopedSettings::ScopedSettings(Scene& scene, const SettingsOverride& o)
    : scene_(scene), saved_(scene.settings) {
  RenderSettings s = scene.settings;
  if (o.method) {
    const auto method = parse_render_method(*o.method);
    if (!method)
      throw InputError("", "method",
                       "unknown render method '" + *o.method +
                           "' (expected one of: " + render_method_names() + ")");
    s.method = *method;
    // The adaptive threshold belongs to the deterministic methods, as a
    // method's own settings do to it: a Monte Carlo method chosen for one
    // call leaves it unused (it takes target_relative_stderr instead).
    if (method_is_monte_carlo(s.method)) s.adaptive_threshold = 0.0;
    // The scene loader's rule, for a method chosen after loading.
    if (scene.sun.enabled && !method_scatters(s.method))
      throw InputError("", "method",
                       "the sun lights clouds through scattering: use \"path-tracer\" or "
                       "\"photonmap\" (emission-absorption has no scattering source)");
  }
  if (o.threads) s.threads = *o.threads;
  if (o.seed) s.seed = *o.seed;
  // Every range in one place (scene/render_settings.h); the argument is named
  // as the Python keyword, or as the scene's setting it conflicts with.
  check_render_settings(s, [](std::string_view key, std::string_view what) {
    const std::string k(key);
    const bool argument = k == "threads" || k == "method";
    return InputError("", argument ? k : "/render/" + k, std::string(what));
  });
  scene.settings = s;
}

void check_time(double t, const std::string& field) {
  if (!std::isfinite(t)) throw InputError("", field, "must be a finite time in seconds");
}

}  // namespace obscura::python
