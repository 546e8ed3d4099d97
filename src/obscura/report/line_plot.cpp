#include "obscura/report/line_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <tuple>
#include <utility>

#include "obscura/core/error.h"
#include "obscura/io/png_file.h"
#include "obscura/report/cairo_canvas.h"

namespace obscura {
namespace {

// ---- ticks ----------------------------------------------------------------

// More is no axis a reader could use, and it bounds the ticks allocated.
constexpr int kMaxTargetTicks = 100;

// m × 10^e, computed so that the result is the double nearest the decimal
// (10^e is exact up to 10^22, and one multiplication or division of exact
// values rounds once): ticks then print and compare as the numbers they name.
double decimal(double m, int e) {
  if (std::abs(e) <= 22) {
    double p = 1.0;
    for (int i = 0; i < std::abs(e); ++i) p *= 10.0;
    return e >= 0 ? m * p : m / p;
  }
  return m * std::pow(10.0, e);
}

// A tick index range [first, last] of multiples of `step` inside [lo, hi]. The
// tolerance keeps ends such as 1/0.2 = 4.999... from being lost to rounding.
std::pair<double, double> multiples_inside(double lo, double hi, double step) {
  constexpr double kTolerance = 1e-9;
  return {std::ceil(lo / step - kTolerance), std::floor(hi / step + kTolerance)};
}

const char* const kSuperscripts[10] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};

std::string superscript(int n) {
  std::string out = n < 0 ? "⁻" : "";
  for (char c : std::to_string(std::abs(n))) out += kSuperscripts[c - '0'];
  return out;
}

// Typographic minus (U+2212): a hyphen is narrower than the digits and reads
// as a dash in tick labels.
std::string with_minus_sign(std::string s) {
  if (!s.empty() && s[0] == '-') s = "−" + s.substr(1);
  return s;
}

// "m×10ⁿ" with as many mantissa digits as the step `10^step_exponent` needs;
// "10ⁿ" for a mantissa of 1 when `bare_decades` (log axes, where decades are
// the norm; on a linear axis "1×10⁷" matches its neighbour "1.5×10⁷").
std::string power_label(double v, int step_exponent, bool bare_decades) {
  if (v == 0.0) return "0";
  const int e = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const std::string s = fmt::format("{:.{}e}", v, std::clamp(e - step_exponent, 0, 16));
  const size_t at = s.find('e');
  std::string mantissa = s.substr(0, at);
  const int exponent = std::atoi(s.c_str() + at + 1);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  if (bare_decades && mantissa == "1") return "10" + superscript(exponent);
  return with_minus_sign(mantissa) + "×10" + superscript(exponent);
}

// Labels for ticks at multiples of 10^step_exponent: plain decimals with the
// step's decimal places while the numbers stay short, powers of ten otherwise.
std::vector<std::string> linear_labels(const std::vector<double>& ticks, int step_exponent) {
  double largest = 0;
  for (double t : ticks) largest = std::max(largest, std::abs(t));
  const bool plain = largest == 0.0 || (largest >= 1e-4 && largest < 1e6);
  std::vector<std::string> labels;
  for (double t : ticks) {
    labels.push_back(plain ? with_minus_sign(fmt::format("{:.{}f}", t, std::max(0, -step_exponent)))
                           : power_label(t, step_exponent, /*bare_decades=*/false));
  }
  return labels;
}

AxisTicks linear_ticks(double lo, double hi, int target) {
  // The candidate steps around span/target: 1, 2, 5 × 10^(e-1 … e+1) always
  // bracket it, so the closest count is among them.
  const int e0 = static_cast<int>(std::floor(std::log10((hi - lo) / target)));
  double best_first = 0, best_last = -1;
  int best_m = 1, best_exponent = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int e = e0 - 1; e <= e0 + 1; ++e) {
    for (int m : {1, 2, 5}) {
      const double step = decimal(m, e);
      const auto [first, last] = multiples_inside(lo, hi, step);
      const double distance = std::abs(last - first + 1 - target);
      // Steps increase through the loop, so "<" prefers the smaller step on a
      // tie: one tick too many reads better than one too few.
      if (distance < best_distance) {
        best_distance = distance;
        best_m = m;
        best_first = first;
        best_last = last;
        best_exponent = e;
      }
    }
  }
  AxisTicks ticks;
  for (double i = best_first; i <= best_last; ++i) {
    ticks.major.push_back(decimal(i * best_m, best_exponent) + 0.0);  // + 0.0: no "−0"
  }
  ticks.labels = linear_labels(ticks.major, best_exponent);
  return ticks;
}

// Labels for m × 10^n on a log axis: decimals while every label is short
// (0.001 … 10000), powers of ten otherwise.
std::vector<std::string> log_labels(const std::vector<double>& ticks) {
  const bool plain =
      std::all_of(ticks.begin(), ticks.end(), [](double t) { return t >= 0.99e-3 && t < 1.01e4; });
  std::vector<std::string> labels;
  for (double t : ticks) {
    const int n = static_cast<int>(std::floor(std::log10(t) + 1e-9));
    labels.push_back(plain ? fmt::format("{:.{}f}", t, std::max(0, -n))
                           : power_label(t, n, /*bare_decades=*/true));
  }
  return labels;
}

AxisTicks log_ticks(double lo, double hi, int target) {
  const double l = std::log10(lo), h = std::log10(hi);
  const int n_lo = static_cast<int>(std::ceil(l - 1e-9));
  const int n_hi = static_cast<int>(std::floor(h + 1e-9));
  auto inside = [&](double v) { return v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9); };

  AxisTicks best;
  double best_distance = std::numeric_limits<double>::infinity();
  auto consider = [&](AxisTicks candidate) {
    const double distance = std::abs(static_cast<double>(candidate.major.size()) - target);
    // Ties go to the fewer ticks: a log axis crowded with labels reads badly.
    if (distance < best_distance ||
        (distance == best_distance && candidate.major.size() < best.major.size())) {
      best_distance = distance;
      best = std::move(candidate);
    }
  };

  // (a) Every k-th decade, k = 1, 2, 5, 10, 20, ... up to one tick or none.
  std::vector<int> strides;
  for (int j = 1; j <= n_hi - n_lo + 1; j *= 10) {
    for (int m : {1, 2, 5}) strides.push_back(m * j);
  }
  for (int k : strides) {
    AxisTicks c;
    for (int n = n_lo; n <= n_hi; ++n) {
      if (n % k == 0)
        c.major.push_back(decimal(1, n));
      else
        c.minor.push_back(decimal(1, n));
    }
    if (k == 1) {
      for (int n = n_lo - 1; n <= n_hi; ++n) {
        for (int m : {2, 5}) {
          if (inside(decimal(m, n))) c.minor.push_back(decimal(m, n));
        }
      }
      std::sort(c.minor.begin(), c.minor.end());
    }
    if (!c.major.empty()) consider(std::move(c));
  }
  // (b) 1, 2, 5 × every decade.
  {
    AxisTicks c;
    for (int n = n_lo - 1; n <= n_hi; ++n) {
      for (int m = 1; m <= 9; ++m) {
        const double v = decimal(m, n);
        if (!inside(v)) continue;
        (m == 1 || m == 2 || m == 5 ? c.major : c.minor).push_back(v);
      }
    }
    if (!c.major.empty()) consider(std::move(c));
  }
  if (!best.major.empty()) best.labels = log_labels(best.major);
  // (c) Under a decade the 1-2-5 ticks may be one or none: plain linear ticks
  // (a log axis that short is nearly linear anyway).
  if (hi / lo < 10) {
    AxisTicks c = linear_ticks(lo, hi, target);
    const double distance = std::abs(static_cast<double>(c.major.size()) - target);
    if (distance < best_distance) best = std::move(c);
  }
  return best;
}

// ---- drawing ----------------------------------------------------------------

// Okabe & Ito (2008), "Color Universal Design": distinguishable under the
// common colour-vision deficiencies. Their yellow is left out: too pale for a
// thin line on white.
constexpr std::array<std::uint8_t, 3> kPalette[] = {
    {0, 114, 178},    // blue
    {213, 94, 0},     // vermillion
    {0, 158, 115},    // bluish green
    {204, 121, 167},  // reddish purple
    {230, 159, 0},    // orange
    {86, 180, 233},   // sky blue
    {0, 0, 0},        // black
};
enum class Marker { kCircle, kSquare, kTriangleUp, kDiamond, kTriangleDown, kCross };
constexpr int kMarkerCount = 6;

// Layout, px (font sizes in cairo user units = px on an image surface).
constexpr int kMargin = 12;
constexpr int kTitleGap = 10;  // title to the plot frame
constexpr int kMajorTick = 5;
constexpr int kMinorTick = 3;
constexpr int kTickLabelGap = 3;  // tick mark to its label
constexpr int kAxisLabelGap = 8;  // tick labels to the axis label
constexpr int kRightMargin = 24;  // room for half of the last x tick label
constexpr int kMinPlotSize = 60;  // plot area, each way
constexpr int kMinCanvas = 240, kMaxCanvas = 8192;
constexpr double kLineWidth = 2.0;  // >= 2, so some pixel row is fully covered
constexpr double kMarkerSize = 8.0;
constexpr double kLegendInset = 8;  // legend box to the frame
constexpr double kLegendPad = 6;
constexpr double kLegendSwatch = 30;  // sample line, px
constexpr double kAutoMargin = 0.05;  // of the span, each side
constexpr double kTitleFontSize = 16;
constexpr double kLabelFontSize = 14;
constexpr double kTickFontSize = 12;
constexpr double kLegendFontSize = 12;
// Clip lines to this far outside the frame before cairo sees them: cairo's
// 24.8 fixed point overflows near 8e6 px, and points far outside an explicit
// range could map beyond that. (Clipping in doubles keeps the visible part to
// ~1e-16 of the segment's length: exact for any data a plot can show, only
// segments over ~1e15 px long, e.g. between ±1e300, come out approximate.)
constexpr double kClipSlack = 1000;
// Lines are stroked in pieces of this many segments: cairo's stroker slows
// down badly on one long self-overlapping path (1e5 noisy points: 41 s as
// one path, 0.65 s in pieces of 64), and round caps hide the seams.
constexpr int kSegmentsPerStroke = 64;
constexpr double kFarOutside = 1e6;  // plot lengths; see AxisMap

using cairo_canvas::CairoPtr;
using cairo_canvas::font_extents;
using cairo_canvas::set_font;
using cairo_canvas::SurfacePtr;
using cairo_canvas::text_advance;

void set_rgb(cairo_t* cr, std::array<std::uint8_t, 3> c) {
  cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

std::string series_name(const PlotSeries& s, size_t index) {
  return fmt::format("series {} (\"{}\")", index, s.label);
}

bool finite_point(const PlotSeries& s, size_t i) {
  return std::isfinite(s.x[i]) && std::isfinite(s.y[i]);
}

void validate(const LinePlot& plot) {
  if (plot.width_px < kMinCanvas || plot.width_px > kMaxCanvas || plot.height_px < kMinCanvas ||
      plot.height_px > kMaxCanvas) {
    throw Error(fmt::format("line plot: canvas must be {}..{} px each way, got {}x{}", kMinCanvas,
                            kMaxCanvas, plot.width_px, plot.height_px));
  }
  if (plot.series.empty()) throw Error("line plot: no series to plot");
  bool any_point = false;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    if (s.label.empty()) {
      throw Error(
          fmt::format("line plot: series {} has no label (the legend names every series)", k));
    }
    if (s.x.size() != s.y.size()) {
      throw Error(fmt::format("line plot: {} has {} x values but {} y values", series_name(s, k),
                              s.x.size(), s.y.size()));
    }
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!finite_point(s, i)) continue;
      any_point = true;
      if (plot.x.log && s.x[i] <= 0) {
        throw Error(fmt::format("line plot: {} point {} has x = {}, but the x axis is logarithmic",
                                series_name(s, k), i, s.x[i]));
      }
      if (plot.y.log && s.y[i] <= 0) {
        throw Error(fmt::format("line plot: {} point {} has y = {}, but the y axis is logarithmic",
                                series_name(s, k), i, s.y[i]));
      }
    }
  }
  if (!any_point) {
    throw Error("line plot: no series has a finite point (NaN and inf are skipped)");
  }
}

// The axis range: explicit ends as given, missing ends from the finite data
// with a margin, computed in log10 for a log axis.
std::pair<double, double> axis_range(const LinePlot& plot, bool is_x) {
  const PlotAxis& axis = is_x ? plot.x : plot.y;
  const char* name = is_x ? "x" : "y";
  for (const auto& end : {axis.min, axis.max}) {
    if (end && (!std::isfinite(*end) || (axis.log && *end <= 0))) {
      throw Error(fmt::format("line plot: {} axis: invalid {} limit {}", name,
                              axis.log ? "logarithmic" : "linear", *end));
    }
  }
  auto to_axis = [&](double v) { return axis.log ? std::log10(v) : v; };
  auto from_axis = [&](double t) { return axis.log ? std::pow(10.0, t) : t; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const PlotSeries& s : plot.series) {
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!finite_point(s, i)) continue;
      const double t = to_axis(is_x ? s.x[i] : s.y[i]);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
  }
  if (axis.min) lo = to_axis(*axis.min);
  if (axis.max) hi = to_axis(*axis.max);
  if (lo == hi && !axis.min && !axis.max) {
    // All data at one value: a range around it (half a decade on a log axis).
    const double half = axis.log ? 0.5 : (lo != 0 ? std::abs(lo) * 0.1 : 1.0);
    lo -= half;
    hi += half;
  } else if (lo < hi) {
    const double span = hi - lo;
    if (!axis.min) lo -= kAutoMargin * span;
    if (!axis.max) hi += kAutoMargin * span;
  }
  if (!(lo < hi)) {
    throw Error(
        fmt::format("line plot: {} axis: empty range [{}, {}] (min must be below max and "
                    "below the data when max is not given, and above it when min is not)",
                    name, from_axis(lo), from_axis(hi)));
  }
  const double out_lo = from_axis(lo), out_hi = from_axis(hi);
  // Range narrower than double precision resolves (or a span that overflows).
  if (!std::isfinite(out_hi - out_lo) ||
      out_hi - out_lo <= 1e-12 * std::max(std::abs(out_lo), std::abs(out_hi))) {
    throw Error(
        fmt::format("line plot: {} axis: range [{}, {}] cannot be resolved", name, out_lo, out_hi));
  }
  return {out_lo, out_hi};
}

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
double min_tick_spacing(const AxisTicks& ticks, const AxisMap& map) {
  double spacing = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < ticks.major.size(); ++i)
    spacing = std::min(spacing, std::abs(map(ticks.major[i]) - map(ticks.major[i - 1])));
  return spacing;
}

struct Point {
  double x, y;
};

// Liang–Barsky: clips segment a→b to the box; false when it misses it.
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

bool has_line(PlotSeries::Style s) { return s != PlotSeries::Style::kMarkers; }
bool has_markers(PlotSeries::Style s) { return s != PlotSeries::Style::kLine; }

void marker_path(cairo_t* cr, Marker marker, double x, double y) {
  const double r = kMarkerSize / 2;
  switch (marker) {
    case Marker::kCircle:
      cairo_new_sub_path(cr);
      cairo_arc(cr, x, y, r, 0, 2 * std::numbers::pi);
      break;
    case Marker::kSquare:
      cairo_rectangle(cr, x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r);
      break;
    case Marker::kTriangleUp:
    case Marker::kTriangleDown: {
      const double s = marker == Marker::kTriangleUp ? 1 : -1;
      cairo_move_to(cr, x, y - s * 1.1 * r);
      cairo_line_to(cr, x + 1.05 * r, y + s * 0.75 * r);
      cairo_line_to(cr, x - 1.05 * r, y + s * 0.75 * r);
      cairo_close_path(cr);
      break;
    }
    case Marker::kDiamond:
      cairo_move_to(cr, x, y - 1.15 * r);
      cairo_line_to(cr, x + 0.85 * r, y);
      cairo_line_to(cr, x, y + 1.15 * r);
      cairo_line_to(cr, x - 0.85 * r, y);
      cairo_close_path(cr);
      break;
    case Marker::kCross:  // stroked, not filled
      cairo_move_to(cr, x - r, y - r);
      cairo_line_to(cr, x + r, y + r);
      cairo_move_to(cr, x - r, y + r);
      cairo_line_to(cr, x + r, y - r);
      break;
  }
}

void draw_marker(cairo_t* cr, Marker marker, double x, double y) {
  marker_path(cr, marker, x, y);
  if (marker == Marker::kCross) {
    cairo_set_line_width(cr, kLineWidth);
    cairo_stroke(cr);
  } else {
    cairo_fill(cr);
  }
}

// A series in canvas px: runs of consecutive finite points (a NaN or inf
// ends a run, so the line breaks there).
std::vector<std::vector<Point>> series_runs(const PlotSeries& s, const AxisMap& xm,
                                            const AxisMap& ym) {
  std::vector<std::vector<Point>> runs;
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

struct Box {
  double left, top, width, height;
};

// How much of the data the legend would hide at `box`: line length inside
// it plus a marker's worth per point inside it.
double ink_inside(const std::vector<std::vector<std::vector<Point>>>& all_runs,
                  const LinePlot& plot, const Box& box) {
  const double x1 = box.left + box.width, y1 = box.top + box.height;
  double ink = 0;
  for (size_t k = 0; k < all_runs.size(); ++k) {
    for (const auto& run : all_runs[k]) {
      for (size_t i = 0; i < run.size(); ++i) {
        const Point p = run[i];
        if (p.x >= box.left && p.x <= x1 && p.y >= box.top && p.y <= y1) ink += kMarkerSize;
        if (i == 0 || !has_line(plot.series[k].style)) continue;
        Point a = run[i - 1], b = p;
        if (clip_segment(a, b, box.left, box.top, x1, y1)) ink += std::hypot(b.x - a.x, b.y - a.y);
      }
    }
  }
  return ink;
}

// Strokes one run of points with the current colour and line width, each
// segment clipped to `clip` first (see kClipSlack). A run of one point has no
// segment: a dot keeps it visible.
void stroke_run(cairo_t* cr, const std::vector<Point>& run, const Box& clip) {
  const double x0 = clip.left, y0 = clip.top;
  const double x1 = clip.left + clip.width, y1 = clip.top + clip.height;
  if (run.size() == 1) {
    const Point p = run[0];
    if (p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, p.x, p.y, kLineWidth, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    return;
  }
  bool pen_at_end = false;  // whether the path currently ends at run[i - 1]
  int segments_in_path = 0;
  for (size_t i = 1; i < run.size(); ++i) {
    Point a = run[i - 1], b = run[i];
    if (!clip_segment(a, b, x0, y0, x1, y1)) {
      pen_at_end = false;
      continue;
    }
    const bool start_clipped = a.x != run[i - 1].x || a.y != run[i - 1].y;
    if (!pen_at_end || start_clipped) cairo_move_to(cr, a.x, a.y);
    cairo_line_to(cr, b.x, b.y);
    pen_at_end = b.x == run[i].x && b.y == run[i].y;
    if (++segments_in_path == kSegmentsPerStroke) {
      cairo_stroke(cr);
      segments_in_path = 0;
      pen_at_end = false;
    }
  }
  cairo_stroke(cr);
}

// Legend: a mostly opaque box at the place chosen in `out` (the data it
// covers were minimised; what remains shows faintly through), and per series
// a sample of its line and marker and its label, one row of `row_h` px each.
void draw_legend(cairo_t* cr, const LinePlot& plot, const std::vector<std::string>& labels,
                 const LinePlotRaster& out, double row_h) {
  cairo_rectangle(cr, std::floor(out.legend_left) + 0.5, std::floor(out.legend_top) + 0.5,
                  out.legend_width, out.legend_height);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
  set_font(cr, kLegendFontSize);
  const cairo_font_extents_t font = font_extents(cr);
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const double row_top = out.legend_top + kLegendPad + row_h * k;
    const double mid = std::floor(row_top + row_h / 2);  // integer: a 2 px line fills two rows
    const double x0 = out.legend_left + kLegendPad;
    set_rgb(cr, plot_series_rgb(k));
    if (has_line(s.style)) {
      cairo_set_line_width(cr, kLineWidth);
      cairo_move_to(cr, x0, mid);
      cairo_line_to(cr, x0 + kLegendSwatch, mid);
      cairo_stroke(cr);
    }
    if (has_markers(s.style)) {
      draw_marker(cr, static_cast<Marker>(k % kMarkerCount), x0 + kLegendSwatch / 2, mid);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, x0 + kLegendSwatch + kLegendPad, mid + (font.ascent - font.descent) / 2);
    cairo_show_text(cr, labels[k].c_str());
  }
}

}  // namespace

AxisTicks nice_ticks(double lo, double hi, int target_count, bool log) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || !std::isfinite(hi - lo)) {
    throw Error(fmt::format("nice_ticks: invalid range [{}, {}]", lo, hi));
  }
  if (target_count < 1 || target_count > kMaxTargetTicks) {
    throw Error(fmt::format("nice_ticks: target tick count must be 1..{}, got {}", kMaxTargetTicks,
                            target_count));
  }
  if (log && lo <= 0) {
    throw Error(fmt::format("nice_ticks: logarithmic range [{}, {}] must be positive", lo, hi));
  }
  // Steps must be normal doubles several digits above the rounding of the
  // ends, or ticks would repeat or be lost.
  if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi)) || hi - lo < 1e-280) {
    throw Error(fmt::format("nice_ticks: range [{}, {}] is too narrow to resolve", lo, hi));
  }
  return log ? log_ticks(lo, hi, target_count) : linear_ticks(lo, hi, target_count);
}

std::array<std::uint8_t, 3> plot_series_rgb(std::size_t index) {
  return kPalette[index % std::size(kPalette)];
}

LinePlotRaster render_line_plot(const LinePlot& plot) {
  validate(plot);
  LinePlotRaster out;
  out.width = plot.width_px;
  out.height = plot.height_px;
  std::tie(out.x_min, out.x_max) = axis_range(plot, /*is_x=*/true);
  std::tie(out.y_min, out.y_max) = axis_range(plot, /*is_x=*/false);

  SurfacePtr surface = cairo_canvas::create_surface(out.width, out.height);
  CairoPtr owner(cairo_create(surface.get()));
  cairo_t* cr = owner.get();

  // Vertical layout first: the plot height decides the y ticks, whose label
  // widths decide the left edge, which decides the plot width and x ticks.
  set_font(cr, kTitleFontSize);
  const cairo_font_extents_t title_font = font_extents(cr);
  set_font(cr, kLabelFontSize);
  const cairo_font_extents_t label_font = font_extents(cr);
  set_font(cr, kTickFontSize);
  const cairo_font_extents_t tick_font = font_extents(cr);

  // Half a tick label above the frame keeps the top y label on the canvas.
  const double top =
      kMargin + (plot.title.empty() ? tick_font.height / 2 : title_font.height + kTitleGap);
  const double x_label_h = plot.x.label.empty() ? 0 : label_font.height + kAxisLabelGap;
  const double bottom =
      out.height - kMargin - x_label_h - tick_font.height - kMajorTick - kTickLabelGap;
  out.plot_top = std::round(top);
  out.plot_height = std::floor(bottom) - out.plot_top;
  if (out.plot_height < kMinPlotSize) {
    throw Error(fmt::format("line plot: {} px height leaves no room for the plot", out.height));
  }
  AxisMap ym{out.y_min, out.y_max, plot.y.log, out.plot_top + out.plot_height, -out.plot_height};

  // About one label per 70 px, fewer until labels are 1.6 lines apart.
  int target = std::clamp(static_cast<int>(out.plot_height / 70), 3, 10);
  out.y_ticks = nice_ticks(out.y_min, out.y_max, target, plot.y.log);
  while (target > 1 && min_tick_spacing(out.y_ticks, ym) < 1.6 * tick_font.height) {
    out.y_ticks = nice_ticks(out.y_min, out.y_max, --target, plot.y.log);
  }
  double y_label_w = 0;
  for (const auto& label : out.y_ticks.labels)
    y_label_w = std::max(y_label_w, text_advance(cr, label));
  const double y_axis_label_w = plot.y.label.empty() ? 0 : label_font.height + kAxisLabelGap;
  out.plot_left = std::ceil(kMargin + y_axis_label_w + y_label_w + kTickLabelGap + kMajorTick);
  out.plot_width = out.width - kRightMargin - out.plot_left;
  if (out.plot_width < kMinPlotSize) {
    throw Error(fmt::format("line plot: {} px width leaves no room for the plot", out.width));
  }
  AxisMap xm{out.x_min, out.x_max, plot.x.log, out.plot_left, out.plot_width};

  // About one label per 90 px, fewer until neighbouring labels have a gap.
  target = std::clamp(static_cast<int>(out.plot_width / 90), 3, 10);
  auto x_labels_fit = [&] {
    double widest = 0;
    for (const auto& label : out.x_ticks.labels) widest = std::max(widest, text_advance(cr, label));
    return min_tick_spacing(out.x_ticks, xm) >= widest + 2 * tick_font.height;
  };
  out.x_ticks = nice_ticks(out.x_min, out.x_max, target, plot.x.log);
  while (target > 1 && !x_labels_fit()) {
    out.x_ticks = nice_ticks(out.x_min, out.x_max, --target, plot.x.log);
  }

  // Series in px, and the legend in the corner that hides the least of them.
  std::vector<std::vector<std::vector<Point>>> runs;
  for (const PlotSeries& s : plot.series) runs.push_back(series_runs(s, xm, ym));
  set_font(cr, kLegendFontSize);
  const cairo_font_extents_t legend_font = font_extents(cr);
  std::vector<std::string> legend_labels;
  double legend_text_w = 0;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    legend_labels.push_back(runs[k].empty() ? plot.series[k].label + " (no finite points)"
                                            : plot.series[k].label);
    legend_text_w = std::max(legend_text_w, text_advance(cr, legend_labels.back()));
  }
  const double row_h = std::ceil(std::max(legend_font.height, kMarkerSize) + 4);
  out.legend_width = std::ceil(2 * kLegendPad + kLegendSwatch + kLegendPad + legend_text_w);
  out.legend_height = std::ceil(2 * kLegendPad + row_h * plot.series.size());
  if (out.legend_width > out.plot_width - 2 * kLegendInset ||
      out.legend_height > out.plot_height - 2 * kLegendInset) {
    throw Error(fmt::format(
        "line plot: the legend ({} series, {}x{} px) does not fit the {}x{} px plot area; "
        "enlarge the plot or shorten the labels",
        plot.series.size(), out.legend_width, out.legend_height, out.plot_width, out.plot_height));
  }
  {
    const double left = out.plot_left + kLegendInset;
    const double right = out.plot_left + out.plot_width - kLegendInset - out.legend_width;
    const double upper = out.plot_top + kLegendInset;
    const double lower = out.plot_top + out.plot_height - kLegendInset - out.legend_height;
    // Preference on a tie: top right, top left, bottom right, bottom left.
    const Point corners[] = {{right, upper}, {left, upper}, {right, lower}, {left, lower}};
    double least = std::numeric_limits<double>::infinity();
    for (const Point& c : corners) {
      // Scored with a halo of the inset: data brushing past the box read as
      // hidden too.
      const double ink =
          ink_inside(runs, plot,
                     {c.x - kLegendInset, c.y - kLegendInset, out.legend_width + 2 * kLegendInset,
                      out.legend_height + 2 * kLegendInset});
      if (ink < least) {
        least = ink;
        out.legend_left = c.x;
        out.legend_top = c.y;
      }
    }
  }

  // Background and grid lines at the major ticks. 1 px lines sit on
  // half-pixel coordinates so they cover exactly one pixel column or row.
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double px0 = out.plot_left, py0 = out.plot_top;
  const double px1 = px0 + out.plot_width, py1 = py0 + out.plot_height;
  auto pixel_line = [](double v) { return std::floor(v) + 0.5; };
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
  for (double v : out.x_ticks.major) {
    cairo_move_to(cr, pixel_line(std::min(xm(v), px1 - 1)), py0);
    cairo_line_to(cr, pixel_line(std::min(xm(v), px1 - 1)), py1);
  }
  for (double v : out.y_ticks.major) {
    cairo_move_to(cr, px0, pixel_line(std::min(ym(v), py1 - 1)));
    cairo_line_to(cr, px1, pixel_line(std::min(ym(v), py1 - 1)));
  }
  cairo_stroke(cr);

  // Series, clipped to the plot area.
  cairo_save(cr);
  cairo_rectangle(cr, px0, py0, out.plot_width, out.plot_height);
  cairo_clip(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  const double cx0 = px0 - kClipSlack, cy0 = py0 - kClipSlack;
  const double cx1 = px1 + kClipSlack, cy1 = py1 + kClipSlack;
  auto near_plot = [&](Point p) { return p.x >= cx0 && p.x <= cx1 && p.y >= cy0 && p.y <= cy1; };
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    set_rgb(cr, plot_series_rgb(k));
    const Marker marker = static_cast<Marker>(k % kMarkerCount);
    if (has_line(s.style)) {
      cairo_set_line_width(cr, kLineWidth);
      for (const auto& run : runs[k]) stroke_run(cr, run, {cx0, cy0, cx1 - cx0, cy1 - cy0});
    }
    if (has_markers(s.style)) {
      for (const auto& run : runs[k]) {
        for (const Point& p : run) {
          if (near_plot(p)) draw_marker(cr, marker, p.x, p.y);
        }
      }
    }
  }
  cairo_restore(cr);

  // Frame just outside the plot area, and outward ticks (they never hide data).
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, px0 - 0.5, py0 - 0.5, out.plot_width + 1, out.plot_height + 1);
  cairo_stroke(cr);
  auto x_tick = [&](double v, double length) {
    const double x = pixel_line(std::min(xm(v), px1 - 1));
    cairo_move_to(cr, x, py1 + 1);
    cairo_line_to(cr, x, py1 + 1 + length);
  };
  auto y_tick = [&](double v, double length) {
    const double y = pixel_line(std::min(ym(v), py1 - 1));
    cairo_move_to(cr, px0 - 1, y);
    cairo_line_to(cr, px0 - 1 - length, y);
  };
  for (double v : out.x_ticks.major) x_tick(v, kMajorTick);
  for (double v : out.x_ticks.minor) x_tick(v, kMinorTick);
  for (double v : out.y_ticks.major) y_tick(v, kMajorTick);
  for (double v : out.y_ticks.minor) y_tick(v, kMinorTick);
  cairo_stroke(cr);

  set_font(cr, kTickFontSize);
  for (size_t i = 0; i < out.x_ticks.major.size(); ++i) {
    const std::string& label = out.x_ticks.labels[i];
    const double w = text_advance(cr, label);
    const double x = std::clamp(xm(out.x_ticks.major[i]) - w / 2, 2.0, out.width - 2 - w);
    cairo_move_to(cr, x, py1 + 1 + kMajorTick + kTickLabelGap + tick_font.ascent);
    cairo_show_text(cr, label.c_str());
  }
  for (size_t i = 0; i < out.y_ticks.major.size(); ++i) {
    const std::string& label = out.y_ticks.labels[i];
    const double y = ym(out.y_ticks.major[i]) + (tick_font.ascent - tick_font.descent) / 2;
    cairo_move_to(cr, px0 - 1 - kMajorTick - kTickLabelGap - text_advance(cr, label), y);
    cairo_show_text(cr, label.c_str());
  }

  // Axis labels, centred on the plot area; the y label reads bottom to top
  // (after rotate(-pi/2) the glyphs' ascent points left).
  set_font(cr, kLabelFontSize);
  if (!plot.x.label.empty()) {
    const double w = text_advance(cr, plot.x.label);
    cairo_move_to(cr, std::max(2.0, px0 + (out.plot_width - w) / 2),
                  out.height - kMargin - label_font.descent);
    cairo_show_text(cr, plot.x.label.c_str());
  }
  if (!plot.y.label.empty()) {
    const double w = text_advance(cr, plot.y.label);
    cairo_save(cr);
    cairo_translate(cr, kMargin + label_font.ascent,
                    std::min(out.height - 2.0, py0 + (out.plot_height + w) / 2));
    cairo_rotate(cr, -std::numbers::pi / 2);
    cairo_move_to(cr, 0, 0);
    cairo_show_text(cr, plot.y.label.c_str());
    cairo_restore(cr);
  }
  if (!plot.title.empty()) {
    set_font(cr, kTitleFontSize);
    const double w = text_advance(cr, plot.title);
    cairo_move_to(cr, std::max(2.0, px0 + (out.plot_width - w) / 2), kMargin + title_font.ascent);
    cairo_show_text(cr, plot.title.c_str());
  }

  draw_legend(cr, plot, legend_labels, out, row_h);

  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("cairo: drawing the line plot failed: {}",
                            cairo_status_to_string(cairo_status(cr))));
  }
  cairo_surface_flush(surface.get());
  out.rgb = cairo_canvas::surface_rgb(surface.get());
  return out;
}

void write_line_plot_png(const std::filesystem::path& path, const LinePlot& plot,
                         const std::string& provenance_json) {
  const std::string file = path.string();
  if (provenance_json.find('\0') != std::string::npos) {
    throw Error(fmt::format("cannot write PNG {}: provenance contains a NUL byte", file));
  }
  const LinePlotRaster raster = render_line_plot(plot);

  std::map<std::string, std::string> chunks;
  if (!provenance_json.empty()) chunks["obscura.provenance"] = provenance_json;
  write_rgb_png(path, raster.width, raster.height, raster.rgb, chunks);
}

}  // namespace obscura
