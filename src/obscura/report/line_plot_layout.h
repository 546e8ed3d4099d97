#pragma once
// Where everything of a line plot goes (report/line_plot.h): the checks of
// the plot, the axis ranges, the plot area left by the title, labels and tick
// labels, the ticks that fit it, and the legend's size and corner. Internal to
// report/.
#include <cairo.h>

#include <string>
#include <utility>
#include <vector>

#include "obscura/report/line_plot.h"
#include "obscura/report/line_plot_geometry.h"

namespace obscura::line_plot {

// Throws Error for a plot render_line_plot refuses (see line_plot.h).
void validate(const LinePlot& plot);

// The axis range: explicit ends as given, missing ends from the finite data
// with a margin, computed in log10 for a log axis.
std::pair<double, double> axis_range(const LinePlot& plot, bool is_x);

// The extents of the four fonts of a plot.
struct PlotFonts {
  cairo_font_extents_t title, label, tick, legend;
};

// What the drawing needs beyond the plot and the raster's geometry.
struct PlotLayout {
  PlotFonts fonts;
  AxisMap x_map, y_map;
  std::vector<SeriesRuns> runs;            // per series, in px
  std::vector<std::string> legend_labels;  // per series
  double legend_row_height = 0;            // px
};

// Lays out `plot` on `out` (whose size and axis ranges are set): fills in the
// plot area, ticks and legend box of `out`, and returns the rest. Measures
// text with `cr`, whose font it changes. Throws Error when the canvas leaves
// no room for the plot area or the legend.
PlotLayout lay_out_line_plot(cairo_t* cr, const LinePlot& plot, LinePlotRaster& out);

}  // namespace obscura::line_plot
