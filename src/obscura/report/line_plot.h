#pragma once
// A small line-plot writer for figures a human reads (convergence curves,
// timings, time series): axes with "nice" ticks, axis labels with units, a
// title, and a legend. Numbers for analysis belong in CSV/JSON; the PNG
// carries the provenance record so a figure found on its own can be traced.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace obscura {

struct PlotSeries {
  enum class Style { kLine, kMarkers, kLineAndMarkers };
  std::string label;  // UTF-8, shown in the legend; must not be empty
  // Equal lengths. A point whose x or y is NaN or ±inf is skipped and breaks
  // the line there; a point left alone between two gaps is drawn as a dot.
  // A series with no finite point is only listed in the legend, marked
  // "(no finite points)".
  std::vector<double> x, y;
  Style style = Style::kLineAndMarkers;
};

struct PlotAxis {
  std::string label;  // UTF-8, with units, e.g. "wall time (s)"
  // Logarithmic (base 10). Every finite value of every series on this axis
  // must be > 0: a non-positive one is an Error naming the series, the point
  // and the value (not skipped: dropping data silently would misreport it).
  bool log = false;
  // Axis range, in the data's units. An end left empty is the finite data's
  // extreme plus a 5 % margin of the span (of log10 of it on a log axis);
  // data all at one value v get v ± 10 % (± 1 for 0), or half a decade either
  // side on a log axis. Points outside the range are clipped at the frame.
  std::optional<double> min, max;
};

struct LinePlot {
  std::string title;  // UTF-8; may be empty
  PlotAxis x, y;
  std::vector<PlotSeries> series;       // at least one with a finite point
  int width_px = 900, height_px = 600;  // canvas size, 240..8192 px each
};

// Ticks of one axis over [lo, hi].
struct AxisTicks {
  // Inside [lo, hi] to 1e-9 of a step, so an end on a tick keeps it.
  std::vector<double> major;        // labelled ticks, increasing
  std::vector<std::string> labels;  // one per major tick, UTF-8 ("0.2", "10⁻⁴", "−5")
  std::vector<double> minor;        // unlabelled ticks, increasing
};

// "Nice numbers" ticks for about `target_count` labelled ticks.
// Linear: multiples of 1, 2 or 5 × 10ⁿ, the step whose tick count is closest
// to the target (ties: the smaller step); no minor ticks.
// Log: the closest to the target of (a) decades, every k-th with k in 1, 2,
// 5, 10, … (minor ticks at 2× and 5× each decade, or at the skipped decades),
// (b) 1, 2, 5 × each decade (minor ticks at 3, 4, 6, 7, 8, 9×), and, for
// ranges under a decade, (c) linear ticks; ties: the fewer ticks.
// Throws Error unless lo < hi are finite, hi − lo exceeds 1e-12 of |lo| and
// |hi| (and 1e-280), 1 <= target_count <= 100, and (log) lo > 0.
AxisTicks nice_ticks(double lo, double hi, int target_count, bool log);

// sRGB colour of series `index` (Okabe & Ito 2008, colour-blind safe),
// cycling after the palette's 7 colours. Markers cycle through 6 shapes, so
// the first 42 series differ in colour or shape.
std::array<std::uint8_t, 3> plot_series_rgb(std::size_t index);

// The drawn plot before PNG encoding (exposed for tests).
struct LinePlotRaster {
  int width = 0, height = 0;      // canvas size, px
  std::vector<std::uint8_t> rgb;  // 3 bytes per px, row-major, top row first
  // The plot area inside the frame, in canvas px (continuous coordinates: the
  // axis minimum maps to plot_left / plot_top + plot_height, the maximum to
  // plot_left + plot_width / plot_top).
  double plot_left = 0, plot_top = 0, plot_width = 0, plot_height = 0;
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  // axis ranges used
  AxisTicks x_ticks, y_ticks;
  // The legend box, in canvas px (inside the plot area, in the corner that
  // covers the fewest data points).
  double legend_left = 0, legend_top = 0, legend_width = 0, legend_height = 0;
};

// Draws `plot`. Throws Error on bad input: no series, every series without a
// finite point, an empty label, x and y of different lengths, a non-positive
// value on a log axis, an invalid range, a bad canvas size, or a legend too
// large for the plot area.
LinePlotRaster render_line_plot(const LinePlot& plot);

// Draws and writes `plot` as an 8-bit RGB PNG of exactly width_px × height_px
// through an AtomicFile (a failed write leaves no file). A non-empty
// `provenance_json` is stored verbatim (UTF-8) as the iTXt chunk
// "obscura.provenance", as in the render previews; it must not contain NUL.
void write_line_plot_png(const std::filesystem::path& path, const LinePlot& plot,
                         const std::string& provenance_json = "");

}  // namespace obscura
