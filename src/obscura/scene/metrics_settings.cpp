#include "obscura/scene/metrics_settings.h"

#include "obscura/io/json_reader.h"
#include "obscura/scene/sensor.h"

namespace obscura {
MetricsSettings parse_metrics_settings(JsonObject& m) {
  MetricsSettings ms;
  ms.transmittance_threshold = m.number_or("transmittance_threshold", ms.transmittance_threshold);
  if (!(ms.transmittance_threshold > 0 && ms.transmittance_threshold < 1))
    throw m.error("transmittance_threshold", "must lie in (0, 1)");
  ms.screened_fraction = m.number_or("screened_fraction", ms.screened_fraction);
  if (!(ms.screened_fraction > 0 && ms.screened_fraction <= 1))
    throw m.error("screened_fraction", "must lie in (0, 1]");
  const long long margin = m.integer_or("background_margin_px", ms.background_margin_px);
  if (margin < 1 || margin > kMaxImageSide)
    throw m.error("background_margin_px", "must be >= 1 pixel");
  ms.background_margin_px = static_cast<int>(margin);
  m.finish();
  return ms;
}

}  // namespace obscura
