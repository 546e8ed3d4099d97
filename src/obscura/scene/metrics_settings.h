#pragma once
// How screening metrics are computed from rendered frames
// (analysis/screening_metrics.h, docs/metrics.md); the scene file's "metrics".
namespace obscura {

struct MetricsSettings {
  // A target pixel counts as screened when its line-of-sight transmittance is
  // below this (the and the field's customary 5 %).
  double transmittance_threshold = 0.05;
  // The target counts as screened while at least this fraction of its pixels
  // are screened: time to screen and screening duration use it.
  double screened_fraction = 0.9;
  // The background of contrast and ΔT: non-target pixels within this many
  // pixels of the target's pixel bounding box (a frame around it).
  int background_margin_px = 8;
};

class JsonObject;
// The scene file's "metrics" object over the defaults; errors name the JSON path.
MetricsSettings parse_metrics_settings(JsonObject& metrics);

}  // namespace obscura
