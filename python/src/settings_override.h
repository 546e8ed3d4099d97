#pragma once
// The keyword arguments render and render_sequence share (method, threads,
// seed) override the scene's settings for one call, as `obscura render
// --threads/--seed` do; the scene's own settings come back afterwards, so a
// Scene renders the same way whatever was asked of it before.
#include <cstdint>
#include <optional>
#include <string>

#include "obscura/scene/scene.h"

namespace obscura::python {

struct SettingsOverride {
  std::optional<std::string> method;
  std::optional<int> threads;
  std::optional<std::uint64_t> seed;
};

class ScopedSettings {
 public:
  // Applies `o` to scene.settings; throws InputError naming the argument
  // (method, threads) for a value the CLI or the scene loader would refuse.
  ScopedSettings(Scene& scene, const SettingsOverride& o);
  ~ScopedSettings() { scene_.settings = saved_; }
  ScopedSettings(const ScopedSettings&) = delete;
  ScopedSettings& operator=(const ScopedSettings&) = delete;

 private:
  Scene& scene_;
  RenderSettings saved_;
};

// Throws InputError("", field, …) unless t is finite (the CLI's --at rule).
void check_time(double t, const std::string& field);

}  // namespace obscura::python
