#pragma once
// Geometry of a line plot in canvas px (report/line_plot.h): points and
// boxes, the map from data values to px along an axis, segment clipping, and
// a series as runs of finite points. Internal to report/.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "obscura/report/line_plot.h"

namespace obscura::line_plot {

// Where AxisMap pins values far outside the axis range, in plot lengths.
inline constexpr double kFarOutside = 1e6;

struct Point {
  double x, y;
};

struct Box {
  double left, top, width, height;
};

// Maps data values to canvas px along one axis.
struct AxisMap {
  double lo = 0, hi = 1;  // axis range, data units
  bool log = false;
  double start = 0, length = 1;  // px of lo; px from lo to hi (negative: upwards)
  double operator()(double v) const {
    const double f = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    // Values far outside the range (v - lo may even overflow) are pinned a
    // million plot lengths out: finite for the clipping, and the visible part
    // of a segment towards them moves by under a millionth of its extent.
    return start + std::clamp(f, -kFarOutside, kFarOutside) * length;
  }
};

// Smallest distance, px, between adjacent major ticks.
double min_tick_spacing(const AxisTicks& ticks, const AxisMap& map);

// Liang–Barsky: clips segment a→b to the box; false when it misses it.
bool clip_segment(Point& a, Point& b, double x0, double y0, double x1, double y1);

// Whether point i of s has finite x and y (others are gaps).
bool finite_point(const PlotSeries& s, std::size_t i);

// A series in canvas px: runs of consecutive finite points (a NaN or inf
// ends a run, so the line breaks there).
using SeriesRuns = std::vector<std::vector<Point>>;
SeriesRuns series_runs(const PlotSeries& s, const AxisMap& xm, const AxisMap& ym);

}  // namespace obscura::line_plot
