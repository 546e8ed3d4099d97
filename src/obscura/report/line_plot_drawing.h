#pragma once
// Drawing a laid-out line plot with cairo (report/line_plot.h): grid, series
// lines and markers, frame, ticks, labels, title and legend. Internal to
// report/.
#include <cairo.h>

#include "obscura/report/line_plot.h"
#include "obscura/report/line_plot_layout.h"

namespace obscura::line_plot {

// Draws `plot` on `cr` (a canvas of out.width × out.height px) where
// lay_out_line_plot placed it.
void draw_line_plot(cairo_t* cr, const LinePlot& plot, const PlotLayout& layout,
                    const LinePlotRaster& out);

}  // namespace obscura::line_plot
