#include "obscura/report/line_plot_drawing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "obscura/report/cairo_canvas.h"
#include "obscura/report/line_plot_geometry.h"
#include "obscura/report/line_plot_style.h"

namespace obscura::line_plot {
namespace {

using cairo_canvas::font_extents;
using cairo_canvas::set_font;
using cairo_canvas::text_advance;

void set_rgb(cairo_t* cr, std::array<std::uint8_t, 3> c) {
  cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

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
void draw_legend(cairo_t* cr, const LinePlot& plot, const PlotLayout& layout,
                 const LinePlotRaster& out) {
  const std::vector<std::string>& labels = layout.legend_labels;
  const double row_h = layout.legend_row_height;
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

// Lines 1 px wide on half-pixel coordinates cover exactly one pixel column
// or row.
double pixel_line(double v) { return std::floor(v) + 0.5; }

// White background and light grey grid lines at the major ticks.
void draw_grid(cairo_t* cr, const PlotLayout& layout, const LinePlotRaster& out) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double px0 = out.plot_left, py0 = out.plot_top;
  const double px1 = px0 + out.plot_width, py1 = py0 + out.plot_height;
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
  for (double v : out.x_ticks.major) {
    cairo_move_to(cr, pixel_line(std::min(layout.x_map(v), px1 - 1)), py0);
    cairo_line_to(cr, pixel_line(std::min(layout.x_map(v), px1 - 1)), py1);
  }
  for (double v : out.y_ticks.major) {
    cairo_move_to(cr, px0, pixel_line(std::min(layout.y_map(v), py1 - 1)));
    cairo_line_to(cr, px1, pixel_line(std::min(layout.y_map(v), py1 - 1)));
  }
  cairo_stroke(cr);
}

// Every series' line and markers, clipped to the plot area.
void draw_series(cairo_t* cr, const LinePlot& plot, const PlotLayout& layout,
                 const LinePlotRaster& out) {
  const double px0 = out.plot_left, py0 = out.plot_top;
  const double px1 = px0 + out.plot_width, py1 = py0 + out.plot_height;
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
      for (const auto& run : layout.runs[k]) stroke_run(cr, run, {cx0, cy0, cx1 - cx0, cy1 - cy0});
    }
    if (has_markers(s.style)) {
      for (const auto& run : layout.runs[k]) {
        for (const Point& p : run) {
          if (near_plot(p)) draw_marker(cr, marker, p.x, p.y);
        }
      }
    }
  }
  cairo_restore(cr);
}

// The frame just outside the plot area, and outward ticks (they never hide
// data).
void draw_frame_and_ticks(cairo_t* cr, const PlotLayout& layout, const LinePlotRaster& out) {
  const double px0 = out.plot_left, py0 = out.plot_top;
  const double px1 = px0 + out.plot_width, py1 = py0 + out.plot_height;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, px0 - 0.5, py0 - 0.5, out.plot_width + 1, out.plot_height + 1);
  cairo_stroke(cr);
  auto x_tick = [&](double v, double length) {
    const double x = pixel_line(std::min(layout.x_map(v), px1 - 1));
    cairo_move_to(cr, x, py1 + 1);
    cairo_line_to(cr, x, py1 + 1 + length);
  };
  auto y_tick = [&](double v, double length) {
    const double y = pixel_line(std::min(layout.y_map(v), py1 - 1));
    cairo_move_to(cr, px0 - 1, y);
    cairo_line_to(cr, px0 - 1 - length, y);
  };
  for (double v : out.x_ticks.major) x_tick(v, kMajorTick);
  for (double v : out.x_ticks.minor) x_tick(v, kMinorTick);
  for (double v : out.y_ticks.major) y_tick(v, kMajorTick);
  for (double v : out.y_ticks.minor) y_tick(v, kMinorTick);
  cairo_stroke(cr);
}

// Labels of the major ticks: centred below the x ticks (kept on the canvas),
// right-aligned left of the y ticks.
void draw_tick_labels(cairo_t* cr, const PlotLayout& layout, const LinePlotRaster& out) {
  const cairo_font_extents_t& tick_font = layout.fonts.tick;
  const double px0 = out.plot_left, py1 = out.plot_top + out.plot_height;
  set_font(cr, kTickFontSize);
  for (size_t i = 0; i < out.x_ticks.major.size(); ++i) {
    const std::string& label = out.x_ticks.labels[i];
    const double w = text_advance(cr, label);
    const double x = std::clamp(layout.x_map(out.x_ticks.major[i]) - w / 2, 2.0, out.width - 2 - w);
    cairo_move_to(cr, x, py1 + 1 + kMajorTick + kTickLabelGap + tick_font.ascent);
    cairo_show_text(cr, label.c_str());
  }
  for (size_t i = 0; i < out.y_ticks.major.size(); ++i) {
    const std::string& label = out.y_ticks.labels[i];
    const double y =
        layout.y_map(out.y_ticks.major[i]) + (tick_font.ascent - tick_font.descent) / 2;
    cairo_move_to(cr, px0 - 1 - kMajorTick - kTickLabelGap - text_advance(cr, label), y);
    cairo_show_text(cr, label.c_str());
  }
}

// Axis labels, centred on the plot area; the y label reads bottom to top
// (after rotate(-pi/2) the glyphs' ascent points left). The title, centred
// above.
void draw_labels_and_title(cairo_t* cr, const LinePlot& plot, const PlotLayout& layout,
                           const LinePlotRaster& out) {
  const cairo_font_extents_t& label_font = layout.fonts.label;
  const double px0 = out.plot_left, py0 = out.plot_top;
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
    cairo_move_to(cr, std::max(2.0, px0 + (out.plot_width - w) / 2),
                  kMargin + layout.fonts.title.ascent);
    cairo_show_text(cr, plot.title.c_str());
  }
}

}  // namespace

void draw_line_plot(cairo_t* cr, const LinePlot& plot, const PlotLayout& layout,
                    const LinePlotRaster& out) {
  draw_grid(cr, layout, out);
  draw_series(cr, plot, layout, out);
  draw_frame_and_ticks(cr, layout, out);
  draw_tick_labels(cr, layout, out);
  draw_labels_and_title(cr, plot, layout, out);
  draw_legend(cr, plot, layout, out);
}

}  // namespace obscura::line_plot
