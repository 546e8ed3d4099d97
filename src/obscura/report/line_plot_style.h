#pragma once
// How line plots look (report/line_plot.h): the palette and marker shapes,
// and the sizes, in px, of the layout, fonts, lines and legend. Internal to
// report/.
#include <array>
#include <cstdint>

#include "obscura/report/line_plot.h"

namespace obscura::line_plot {

// Okabe & Ito (2008), "Color Universal Design": distinguishable under the
// common colour-vision deficiencies. Their yellow is left out: too pale for a
// thin line on white.
inline constexpr std::array<std::uint8_t, 3> kPalette[] = {
    {0, 114, 178},    // blue
    {213, 94, 0},     // vermillion
    {0, 158, 115},    // bluish green
    {204, 121, 167},  // reddish purple
    {230, 159, 0},    // orange
    {86, 180, 233},   // sky blue
    {0, 0, 0},        // black
};
enum class Marker { kCircle, kSquare, kTriangleUp, kDiamond, kTriangleDown, kCross };
inline constexpr int kMarkerCount = 6;

// Layout, px (font sizes in cairo user units = px on an image surface).
inline constexpr int kMargin = 12;
inline constexpr int kTitleGap = 10;  // title to the plot frame
inline constexpr int kMajorTick = 5;
inline constexpr int kMinorTick = 3;
inline constexpr int kTickLabelGap = 3;  // tick mark to its label
inline constexpr int kAxisLabelGap = 8;  // tick labels to the axis label
inline constexpr int kRightMargin = 24;  // room for half of the last x tick label
inline constexpr int kMinPlotSize = 60;  // plot area, each way
inline constexpr int kMinCanvas = 240, kMaxCanvas = 8192;
inline constexpr double kLineWidth = 2.0;  // >= 2, so some pixel row is fully covered
inline constexpr double kMarkerSize = 8.0;
inline constexpr double kLegendInset = 8;  // legend box to the frame
inline constexpr double kLegendPad = 6;
inline constexpr double kLegendSwatch = 30;  // sample line, px
inline constexpr double kAutoMargin = 0.05;  // of the span, each side
inline constexpr double kTitleFontSize = 16;
inline constexpr double kLabelFontSize = 14;
inline constexpr double kTickFontSize = 12;
inline constexpr double kLegendFontSize = 12;
// Clip lines to this far outside the frame before cairo sees them: cairo's
// 24.8 fixed point overflows near 8e6 px, and points far outside an explicit
// range could map beyond that. (Clipping in doubles keeps the visible part to
// ~1e-16 of the segment's length: exact for any data a plot can show, only
// segments over ~1e15 px long, e.g. between ±1e300, come out approximate.)
inline constexpr double kClipSlack = 1000;
// Lines are stroked in pieces of this many segments: cairo's stroker slows
// down badly on one long self-overlapping path (1e5 noisy points: 41 s as
// one path, 0.65 s in pieces of 64), and round caps hide the seams.
inline constexpr int kSegmentsPerStroke = 64;

inline bool has_line(PlotSeries::Style s) { return s != PlotSeries::Style::kMarkers; }
inline bool has_markers(PlotSeries::Style s) { return s != PlotSeries::Style::kLine; }

}  // namespace obscura::line_plot
