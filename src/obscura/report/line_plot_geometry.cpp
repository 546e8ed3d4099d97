#include "obscura/report/line_plot_geometry.h"

#include <limits>

namespace obscura::line_plot {

double min_tick_spacing(const AxisTicks& ticks, const AxisMap& map) {
  double spacing = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < ticks.major.size(); ++i)
    spacing = std::min(spacing, std::abs(map(ticks.major[i]) - map(ticks.major[i - 1])));
  return spacing;
}

bool clip_segment(Point& a, Point& b, double x0, double y0, double x1, double y1) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const Point a0 = a;
  a = {a0.x + t0 * dx, a0.y + t0 * dy};
  b = {a0.x + t1 * dx, a0.y + t1 * dy};
  return true;
}

bool finite_point(const PlotSeries& s, size_t i) {
  return std::isfinite(s.x[i]) && std::isfinite(s.y[i]);
}

SeriesRuns series_runs(const PlotSeries& s, const AxisMap& xm, const AxisMap& ym) {
  SeriesRuns runs;
  bool open = false;
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (!finite_point(s, i)) {
      open = false;
      continue;
    }
    if (!open) runs.emplace_back();
    open = true;
    runs.back().push_back({xm(s.x[i]), ym(s.y[i])});
  }
  return runs;
}

}  // namespace obscura::line_plot
