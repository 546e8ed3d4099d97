#include "obscura/report/line_plot_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/report/cairo_canvas.h"
#include "obscura/report/line_plot_style.h"

namespace obscura::line_plot {
namespace {

using cairo_canvas::font_extents;
using cairo_canvas::set_font;
using cairo_canvas::text_advance;

std::string series_name(const PlotSeries& s, size_t index) {
  return fmt::format("series {} (\"{}\")", index, s.label);
}

// How much of the data the legend would hide at `box`: line length inside
// it plus a marker's worth per point inside it.
double ink_inside(const std::vector<SeriesRuns>& all_runs, const LinePlot& plot, const Box& box) {
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

PlotFonts measure_fonts(cairo_t* cr) {
  PlotFonts fonts;
  set_font(cr, kTitleFontSize);
  fonts.title = font_extents(cr);
  set_font(cr, kLabelFontSize);
  fonts.label = font_extents(cr);
  set_font(cr, kTickFontSize);
  fonts.tick = font_extents(cr);
  set_font(cr, kLegendFontSize);
  fonts.legend = font_extents(cr);
  return fonts;
}

// The plot area's top and height: below the title (or half a tick label,
// which keeps the top y label on the canvas), above the x tick labels and
// the x label.
void place_vertically(const LinePlot& plot, const PlotFonts& fonts, LinePlotRaster& out) {
  const double top =
      kMargin + (plot.title.empty() ? fonts.tick.height / 2 : fonts.title.height + kTitleGap);
  const double x_label_h = plot.x.label.empty() ? 0 : fonts.label.height + kAxisLabelGap;
  const double bottom =
      out.height - kMargin - x_label_h - fonts.tick.height - kMajorTick - kTickLabelGap;
  out.plot_top = std::round(top);
  out.plot_height = std::floor(bottom) - out.plot_top;
  if (out.plot_height < kMinPlotSize) {
    throw Error(fmt::format("line plot: {} px height leaves no room for the plot", out.height));
  }
}

// About one label per 70 px, fewer until labels are 1.6 lines apart.
AxisTicks choose_y_ticks(const LinePlot& plot, const PlotFonts& fonts, const LinePlotRaster& out,
                         const AxisMap& ym) {
  int target = std::clamp(static_cast<int>(out.plot_height / 70), 3, 10);
  AxisTicks ticks = nice_ticks(out.y_min, out.y_max, target, plot.y.log);
  while (target > 1 && min_tick_spacing(ticks, ym) < 1.6 * fonts.tick.height) {
    ticks = nice_ticks(out.y_min, out.y_max, --target, plot.y.log);
  }
  return ticks;
}

// The plot area's left edge and width: right of the y label and the widest y
// tick label, leaving room on the right for half the last x tick label.
void place_horizontally(cairo_t* cr, const LinePlot& plot, const PlotFonts& fonts,
                        LinePlotRaster& out) {
  set_font(cr, kTickFontSize);
  double y_label_w = 0;
  for (const auto& label : out.y_ticks.labels)
    y_label_w = std::max(y_label_w, text_advance(cr, label));
  const double y_axis_label_w = plot.y.label.empty() ? 0 : fonts.label.height + kAxisLabelGap;
  out.plot_left = std::ceil(kMargin + y_axis_label_w + y_label_w + kTickLabelGap + kMajorTick);
  out.plot_width = out.width - kRightMargin - out.plot_left;
  if (out.plot_width < kMinPlotSize) {
    throw Error(fmt::format("line plot: {} px width leaves no room for the plot", out.width));
  }
}

// About one label per 90 px, fewer until neighbouring labels have a gap.
AxisTicks choose_x_ticks(cairo_t* cr, const LinePlot& plot, const PlotFonts& fonts,
                         const LinePlotRaster& out, const AxisMap& xm) {
  set_font(cr, kTickFontSize);
  int target = std::clamp(static_cast<int>(out.plot_width / 90), 3, 10);
  AxisTicks ticks = nice_ticks(out.x_min, out.x_max, target, plot.x.log);
  auto labels_fit = [&] {
    double widest = 0;
    for (const auto& label : ticks.labels) widest = std::max(widest, text_advance(cr, label));
    return min_tick_spacing(ticks, xm) >= widest + 2 * fonts.tick.height;
  };
  while (target > 1 && !labels_fit()) {
    ticks = nice_ticks(out.x_min, out.x_max, --target, plot.x.log);
  }
  return ticks;
}

// The legend's labels (a series without a finite point says so), row height
// and box size; throws Error if the box does not fit the plot area.
void size_legend(cairo_t* cr, const LinePlot& plot, PlotLayout& layout, LinePlotRaster& out) {
  set_font(cr, kLegendFontSize);
  double legend_text_w = 0;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    layout.legend_labels.push_back(layout.runs[k].empty()
                                       ? plot.series[k].label + " (no finite points)"
                                       : plot.series[k].label);
    legend_text_w = std::max(legend_text_w, text_advance(cr, layout.legend_labels.back()));
  }
  const double row_h = std::ceil(std::max(layout.fonts.legend.height, kMarkerSize) + 4);
  layout.legend_row_height = row_h;
  out.legend_width = std::ceil(2 * kLegendPad + kLegendSwatch + kLegendPad + legend_text_w);
  out.legend_height = std::ceil(2 * kLegendPad + row_h * plot.series.size());
  if (out.legend_width > out.plot_width - 2 * kLegendInset ||
      out.legend_height > out.plot_height - 2 * kLegendInset) {
    throw Error(fmt::format(
        "line plot: the legend ({} series, {}x{} px) does not fit the {}x{} px plot area; "
        "enlarge the plot or shorten the labels",
        plot.series.size(), out.legend_width, out.legend_height, out.plot_width, out.plot_height));
  }
}

// The legend goes in the corner of the plot area that hides the least data.
void place_legend(const LinePlot& plot, const std::vector<SeriesRuns>& runs, LinePlotRaster& out) {
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

}  // namespace

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

// Vertical layout first: the plot height decides the y ticks, whose label
// widths decide the left edge, which decides the plot width and x ticks; then
// the series in px, which decide the legend's corner.
PlotLayout lay_out_line_plot(cairo_t* cr, const LinePlot& plot, LinePlotRaster& out) {
  PlotLayout layout;
  layout.fonts = measure_fonts(cr);
  place_vertically(plot, layout.fonts, out);
  layout.y_map = {out.y_min, out.y_max, plot.y.log, out.plot_top + out.plot_height,
                  -out.plot_height};
  out.y_ticks = choose_y_ticks(plot, layout.fonts, out, layout.y_map);
  place_horizontally(cr, plot, layout.fonts, out);
  layout.x_map = {out.x_min, out.x_max, plot.x.log, out.plot_left, out.plot_width};
  out.x_ticks = choose_x_ticks(cr, plot, layout.fonts, out, layout.x_map);
  for (const PlotSeries& s : plot.series)
    layout.runs.push_back(series_runs(s, layout.x_map, layout.y_map));
  size_legend(cr, plot, layout, out);
  place_legend(plot, layout.runs, out);
  return layout;
}

}  // namespace obscura::line_plot
