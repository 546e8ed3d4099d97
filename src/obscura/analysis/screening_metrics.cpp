#include "obscura/analysis/screening_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "obscura/core/error.h"

namespace obscura {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// No blackbody has a band radiance <= 0: the temperature is undefined there
// (not 0 K, which would make ΔT of two black regions a meaningful 0).
double apparent_temperature_or_nan(const BandQuadrature& q, double radiance) {
  return std::isfinite(radiance) && radiance > 0 ? q.apparent_temperature(radiance) : kNaN;
}

}  // namespace

double percentile_of_sorted(const std::vector<double>& sorted, double p) {
  if (!(p >= 0.0 && p <= 1.0)) throw Error(fmt::format("percentile: p = {} is outside [0, 1]", p));
  if (sorted.empty()) return kNaN;
  const double h = (static_cast<double>(sorted.size()) - 1.0) * p;
  const std::size_t k = static_cast<std::size_t>(std::floor(h));
  if (k + 1 >= sorted.size()) return sorted.back();
  return sorted[k] + (h - static_cast<double>(k)) * (sorted[k + 1] - sorted[k]);
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return percentile_of_sorted(values, p);
}

std::vector<ScreeningMetrics> screening_metrics(const SensorImage& image, const TargetMask& mask,
                                                const MetricsSettings& settings,
                                                const RenderSettings& render, double time_s) {
  if (image.width != mask.width || image.height != mask.height)
    throw Error(
        fmt::format("screening metrics: the {}x{} image of sensor {} does not match the {}x{} "
                    "target mask of {}",
                    image.width, image.height, image.sensor, mask.width, mask.height, mask.sensor));
  std::vector<ScreeningMetrics> out;
  std::vector<double> target_t;
  target_t.reserve(static_cast<std::size_t>(mask.target_pixels));
  for (const BandImage& b : image.bands) {
    ScreeningMetrics m;
    m.time_s = time_s;
    m.sensor = image.sensor;
    m.band = b.band;
    target_t.clear();
    double target_l = 0, background_l = 0, t_sum = 0;
    int screened = 0;
    for (std::size_t i = 0; i < mask.labels.size(); ++i) {
      if (mask.labels[i] == MaskLabel::kTarget) {
        const double t = b.transmittance[i];
        target_l += b.radiance[i];
        t_sum += t;
        target_t.push_back(t);
        if (t < settings.transmittance_threshold) ++screened;
      } else if (mask.labels[i] == MaskLabel::kBackground) {
        background_l += b.radiance[i];
      }
    }
    m.target_pixels = mask.target_pixels;
    m.background_pixels = mask.background_pixels;
    const double nt = mask.target_pixels, nb = mask.background_pixels;
    m.transmittance_mean = nt > 0 ? t_sum / nt : kNaN;
    std::sort(target_t.begin(), target_t.end());
    m.transmittance_p10 = percentile_of_sorted(target_t, 0.1);
    m.transmittance_p50 = percentile_of_sorted(target_t, 0.5);
    m.transmittance_p90 = percentile_of_sorted(target_t, 0.9);
    m.screened_fraction = nt > 0 ? screened / nt : kNaN;
    m.target_radiance = nt > 0 ? target_l / nt : kNaN;
    m.background_radiance = nb > 0 ? background_l / nb : kNaN;
    m.contrast = m.background_radiance > 0
                     ? (m.target_radiance - m.background_radiance) / m.background_radiance
                     : kNaN;
    // The same quadrature as the renderer's (as region_stats): a uniform
    // blackbody region gives its temperature.
    const BandQuadrature q(b.band, render.spectral_nodes(b.band), 0.0);
    m.target_apparent_temperature_k = apparent_temperature_or_nan(q, m.target_radiance);
    m.background_apparent_temperature_k = apparent_temperature_or_nan(q, m.background_radiance);
    m.delta_t_k = m.target_apparent_temperature_k - m.background_apparent_temperature_k;
    out.push_back(std::move(m));
  }
  return out;
}

double screening_reference_time_s(const Scene& scene) {
  if (scene.animated_clouds.empty()) return 0.0;
  double t = std::numeric_limits<double>::infinity();
  for (const auto& c : scene.animated_clouds) t = std::min(t, c->activation_s());
  return t;
}

ScreeningTimes screening_times(const std::vector<double>& times_s,
                               const std::vector<double>& screened_fractions, double criterion,
                               double reference_time_s) {
  const std::size_t n = times_s.size();
  if (screened_fractions.size() != n)
    throw Error(fmt::format("screening times: {} times but {} screened fractions", n,
                            screened_fractions.size()));
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (!(times_s[i] < times_s[i + 1]))
      throw Error(fmt::format("screening times: times must increase strictly ({} then {} s)",
                              times_s[i], times_s[i + 1]));
  ScreeningTimes out;
  if (n == 0 || std::any_of(screened_fractions.begin(), screened_fractions.end(),
                            [](double f) { return std::isnan(f); }))
    return out;
  const auto& f = screened_fractions;
  // Where the line from frame i to frame i + 1 crosses the criterion (one of
  // the two frames meets it, the other does not).
  auto crossing = [&](std::size_t i) {
    return times_s[i] + (criterion - f[i]) / (f[i + 1] - f[i]) * (times_s[i + 1] - times_s[i]);
  };
  bool open = f[0] >= criterion;
  double start = times_s[0];
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const bool next = f[i + 1] >= criterion;
    if (open && !next) {
      out.intervals.push_back({start, crossing(i)});
      open = false;
    } else if (!open && next) {
      start = crossing(i);
      open = true;
    }
  }
  if (open) out.intervals.push_back({start, times_s[n - 1]});

  double total = 0;
  for (const auto& iv : out.intervals) total += iv.until_s - iv.from_s;
  out.screening_duration_s = total;
  if (!out.intervals.empty()) {
    out.screened_from_s = out.intervals.front().from_s;
    out.screened_until_s = out.intervals.front().until_s;
    out.time_to_screen_s = out.intervals.front().from_s - reference_time_s;
  }
  return out;
}

std::vector<std::vector<const ScreeningMetrics*>> group_screening_series(
    const std::vector<ScreeningMetrics>& rows) {
  std::vector<std::vector<const ScreeningMetrics*>> groups;
  for (const ScreeningMetrics& r : rows) {
    auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return g.front()->sensor == r.sensor && g.front()->band.name() == r.band.name();
    });
    if (group == groups.end())
      groups.push_back({&r});
    else
      group->push_back(&r);
  }
  for (auto& g : groups)
    std::stable_sort(g.begin(), g.end(),
                     [](const auto* a, const auto* b) { return a->time_s < b->time_s; });
  return groups;
}

std::vector<ScreeningSeries> summarize_screening(const std::vector<ScreeningMetrics>& rows,
                                                 const MetricsSettings& settings,
                                                 double reference_time_s) {
  std::vector<ScreeningSeries> out;
  for (const auto& members : group_screening_series(rows)) {
    const ScreeningMetrics* first = members.front();
    ScreeningSeries s;
    s.sensor = first->sensor;
    s.band = first->band;
    s.target_pixels = first->target_pixels;
    std::vector<double> fractions;
    s.max_screened_fraction = s.min_transmittance_mean = s.min_transmittance_mean_time_s = kNaN;
    for (const ScreeningMetrics* m : members) {
      s.times_s.push_back(m->time_s);
      fractions.push_back(m->screened_fraction);
      if (!std::isnan(m->screened_fraction) &&
          (std::isnan(s.max_screened_fraction) || m->screened_fraction > s.max_screened_fraction))
        s.max_screened_fraction = m->screened_fraction;
      if (!std::isnan(m->transmittance_mean) &&
          (std::isnan(s.min_transmittance_mean) ||
           m->transmittance_mean < s.min_transmittance_mean)) {
        s.min_transmittance_mean = m->transmittance_mean;
        s.min_transmittance_mean_time_s = m->time_s;
      }
    }
    s.screening =
        screening_times(s.times_s, fractions, settings.screened_fraction, reference_time_s);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace obscura
