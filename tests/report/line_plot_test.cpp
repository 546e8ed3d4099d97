#include "obscura/report/line_plot.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/report/png_preview.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;
using Rgb = std::array<std::uint8_t, 3>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class LinePlotTest : public testing::TempDirTest {};

// A PNG read back with cairo, independently of the writer's libpng code.
struct Image {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;
  Rgb at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

Image read_png_cairo(const fs::path& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  Image image;
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    ADD_FAILURE() << "cairo cannot read " << path << ": "
                  << cairo_status_to_string(cairo_surface_status(s));
    cairo_surface_destroy(s);
    return image;
  }
  image.width = cairo_image_surface_get_width(s);
  image.height = cairo_image_surface_get_height(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::uint32_t argb;
      std::memcpy(&argb, data + static_cast<size_t>(y) * stride + static_cast<size_t>(x) * 4, 4);
      image.pixels.push_back({static_cast<std::uint8_t>(argb >> 16),
                              static_cast<std::uint8_t>(argb >> 8),
                              static_cast<std::uint8_t>(argb)});
    }
  }
  cairo_surface_destroy(s);
  return image;
}

Image from_raster(const LinePlotRaster& r) {
  Image image{r.width, r.height, {}};
  for (size_t i = 0; i < r.rgb.size(); i += 3)
    image.pixels.push_back({r.rgb[i], r.rgb[i + 1], r.rgb[i + 2]});
  return image;
}

// Within a few levels per channel: the centre of a 2 px line is fully covered
// and exact, but allow for rounding in cairo's compositing.
bool near(Rgb a, Rgb b) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(int{a[c]} - int{b[c]}) > 6) return false;
  }
  return true;
}

// Rows of column x whose pixel has colour c, outside the legend box (whose
// samples carry every series' colour).
std::vector<int> rows_with(const Image& image, const LinePlotRaster& r, int x, Rgb c) {
  std::vector<int> rows;
  const bool legend_column = x >= r.legend_left && x <= r.legend_left + r.legend_width;
  for (int y = 0; y < image.height; ++y) {
    if (legend_column && y >= r.legend_top && y <= r.legend_top + r.legend_height) continue;
    if (near(image.at(x, y), c)) rows.push_back(y);
  }
  return rows;
}

PlotSeries series(std::string label, std::vector<double> x, std::vector<double> y,
                  PlotSeries::Style style = PlotSeries::Style::kLine) {
  PlotSeries s;
  s.label = std::move(label);
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = style;
  return s;
}

// A horizontal series at height v from x0 to x1 (11 points).
PlotSeries horizontal(std::string label, double v, double x0 = 0, double x1 = 10) {
  PlotSeries s = series(std::move(label), {}, {});
  for (int i = 0; i <= 10; ++i) {
    s.x.push_back(x0 + (x1 - x0) * i / 10);
    s.y.push_back(v);
  }
  return s;
}

LinePlot simple_plot() {
  LinePlot plot;
  plot.title = "test plot";
  plot.x.label = "time (s)";
  plot.y.label = "transmittance (1)";
  plot.series = {horizontal("a", 0.5)};
  return plot;
}

// ---- nice_ticks ---------------------------------------------------------------

TEST(NiceTicks, UnitRangeStepsByTwoTenths) {
  const AxisTicks t = nice_ticks(0, 1, 5, false);
  // Exact: ticks are built as (i·m) / 10^k, the doubles nearest the decimals.
  EXPECT_EQ(t.major, (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_TRUE(t.minor.empty());
  EXPECT_FALSE(std::signbit(t.major[0]));  // never "−0.0"
}

TEST(NiceTicks, OddRangeGetsRoundTicksInside) {
  const AxisTicks five = nice_ticks(0.013, 0.87, 5, false);
  EXPECT_EQ(five.major, (std::vector<double>{0.2, 0.4, 0.6, 0.8}));
  EXPECT_EQ(five.labels, (std::vector<std::string>{"0.2", "0.4", "0.6", "0.8"}));
  const AxisTicks eight = nice_ticks(0.013, 0.87, 8, false);
  EXPECT_EQ(eight.major, (std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}));
  EXPECT_EQ(nice_ticks(-1, 1, 5, false).labels,
            (std::vector<std::string>{"−1.0", "−0.5", "0.0", "0.5", "1.0"}));
  EXPECT_EQ(nice_ticks(0, 2000, 5, false).labels,
            (std::vector<std::string>{"0", "500", "1000", "1500", "2000"}));
  // 5 ticks (step 500) and 3 (step 1000) are equally far from 4: the smaller step.
  EXPECT_EQ(nice_ticks(0, 2000, 4, false).major, (std::vector<double>{0, 500, 1000, 1500, 2000}));
  EXPECT_EQ(nice_ticks(0, 2000, 3, false).major, (std::vector<double>{0, 1000, 2000}));
}

TEST(NiceTicks, LargeAndTinyNumbersUsePowersOfTen) {
  EXPECT_EQ(nice_ticks(-3e6, 2.5e7, 5, false).labels,
            (std::vector<std::string>{"0", "5×10⁶", "1×10⁷", "1.5×10⁷", "2×10⁷", "2.5×10⁷"}));
  EXPECT_EQ(nice_ticks(2e-5, 9e-5, 4, false).labels,
            (std::vector<std::string>{"2×10⁻⁵", "4×10⁻⁵", "6×10⁻⁵", "8×10⁻⁵"}));
}

TEST(NiceTicks, LogRangeGetsDecadesWithMinorTwosAndFives) {
  const AxisTicks t = nice_ticks(1e-3, 10, 5, true);
  EXPECT_EQ(t.major, (std::vector<double>{1e-3, 1e-2, 0.1, 1, 10}));
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.001", "0.01", "0.1", "1", "10"}));
  EXPECT_EQ(t.minor, (std::vector<double>{2e-3, 5e-3, 2e-2, 5e-2, 0.2, 0.5, 2, 5}));
}

TEST(NiceTicks, LogRangesOfOtherWidths) {
  // Two decades: the 1-2-5 ticks come closer to 8 than the 3 decades.
  const AxisTicks two = nice_ticks(1, 100, 8, true);
  EXPECT_EQ(two.major, (std::vector<double>{1, 2, 5, 10, 20, 50, 100}));
  EXPECT_EQ(two.labels, (std::vector<std::string>{"1", "2", "5", "10", "20", "50", "100"}));
  EXPECT_EQ(two.minor.size(), 12u);  // 3, 4, 6, 7, 8, 9 in each decade
  // Seven decades for 5 ticks: every other decade, the rest minor.
  const AxisTicks wide = nice_ticks(1e-9, 1e-2, 5, true);
  EXPECT_EQ(wide.major, (std::vector<double>{1e-8, 1e-6, 1e-4, 1e-2}));
  EXPECT_EQ(wide.labels, (std::vector<std::string>{"10⁻⁸", "10⁻⁶", "10⁻⁴", "10⁻²"}));
  EXPECT_EQ(wide.minor, (std::vector<double>{1e-9, 1e-7, 1e-5, 1e-3}));
  // Under a decade: linear ticks.
  EXPECT_EQ(nice_ticks(3, 8, 5, true).major, (std::vector<double>{3, 4, 5, 6, 7, 8}));
  // Past 10⁴ every label is a power, so the axis reads uniformly.
  EXPECT_EQ(nice_ticks(1, 1e6, 4, true).labels,
            (std::vector<std::string>{"10⁰", "10²", "10⁴", "10⁶"}));
}

TEST(NiceTicks, PropertiesOverManyRanges) {
  // Ranges from 1e-7 to 1e8 wide at assorted offsets: the ticks must be
  // increasing, inside the range, evenly spaced by 1, 2 or 5 × 10ⁿ, as many
  // as the labels, and not far from the target.
  for (int e = -7; e <= 8; ++e) {
    for (double width_factor : {1.0, 1.3, 2.7, 4.9, 7.7}) {
      for (double offset : {-0.37, 0.0, 0.5, 3.0, 1000.0}) {
        for (int target : {2, 5, 8}) {
          const double width = width_factor * std::pow(10.0, e);
          const double lo = offset * width, hi = lo + width;
          const AxisTicks t = nice_ticks(lo, hi, target, false);
          SCOPED_TRACE(::testing::Message() << "[" << lo << ", " << hi << "] target " << target);
          ASSERT_GE(t.major.size(), 1u);
          EXPECT_EQ(t.labels.size(), t.major.size());
          EXPECT_LE(t.major.size(), 2u * target + 1);
          if (target >= 5) {
            EXPECT_GE(t.major.size(), 3u);
          }
          for (double v : t.major) {
            EXPECT_GE(v, lo - 1e-9 * width);
            EXPECT_LE(v, hi + 1e-9 * width);
          }
          if (t.major.size() < 2) continue;
          const double step = t.major[1] - t.major[0];
          const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
          EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                      std::abs(mantissa - 5) < 1e-6)
              << "step " << step;
          for (size_t i = 1; i < t.major.size(); ++i) {
            EXPECT_NEAR(t.major[i] - t.major[i - 1], step, 1e-9 * step + 1e-12 * std::abs(lo));
          }
          // Labels distinct: a label repeated means too few digits.
          EXPECT_EQ(std::set<std::string>(t.labels.begin(), t.labels.end()).size(),
                    t.labels.size());
        }
      }
    }
  }
}

TEST(NiceTicks, ExtremeRangesGiveFiniteTicks) {
  for (const auto& [lo, hi, log] : {std::tuple{0.0, 1e308, false}, std::tuple{-1e308, 0.0, false},
                                    std::tuple{1e-300, 1e300, true}, std::tuple{1e300, 1e308, true},
                                    std::tuple{1e-12, 2e-12, false}}) {
    for (int target : {1, 5, 100}) {
      const AxisTicks t = nice_ticks(lo, hi, target, log);
      SCOPED_TRACE(::testing::Message() << lo << " " << hi << " " << target);
      ASSERT_FALSE(t.major.empty());
      for (double v : t.major) {
        EXPECT_TRUE(std::isfinite(v)) << v;
        EXPECT_GE(v, lo - 1e-9 * std::abs(lo));
        EXPECT_LE(v, hi + 1e-9 * std::abs(hi));
      }
    }
  }
}

TEST(NiceTicks, BadInputThrows) {
  EXPECT_THROW(nice_ticks(1, 1, 5, false), Error);
  EXPECT_THROW(nice_ticks(2, 1, 5, false), Error);
  EXPECT_THROW(nice_ticks(kNaN, 1, 5, false), Error);
  EXPECT_THROW(nice_ticks(0, kInf, 5, false), Error);
  EXPECT_THROW(nice_ticks(-1e308, 1e308, 5, false), Error);  // span overflows
  EXPECT_THROW(nice_ticks(1, 1 + 1e-15, 5, false), Error);   // below double resolution
  EXPECT_THROW(nice_ticks(0, 1e-300, 5, false), Error);      // steps would be subnormal
  EXPECT_THROW(nice_ticks(0, 1, 0, false), Error);
  EXPECT_THROW(nice_ticks(0, 1, 101, false), Error);
  EXPECT_THROW(nice_ticks(0, 10, 5, true), Error);
  EXPECT_THROW(nice_ticks(-1, 10, 5, true), Error);
}

TEST(PlotSeriesRgb, SevenDistinctColoursThenCycles) {
  std::set<Rgb> colours;
  for (size_t i = 0; i < 7; ++i) colours.insert(plot_series_rgb(i));
  EXPECT_EQ(colours.size(), 7u);
  EXPECT_FALSE(colours.count(Rgb{255, 255, 255}));    // none invisible on the background
  EXPECT_EQ(plot_series_rgb(0), (Rgb{0, 114, 178}));  // Okabe–Ito blue
  EXPECT_EQ(plot_series_rgb(7), plot_series_rgb(0));
}

// ---- rendering and writing ------------------------------------------------------

TEST_F(LinePlotTest, WritesPngOfRequestedSizeWithProvenance) {
  LinePlot plot = simple_plot();
  plot.width_px = 640;
  plot.height_px = 420;
  const std::string provenance = R"({"software":"obscura","inputs":[{"path":"szene_ü.json"}]})";
  const fs::path path = dir_ / "plots" / "convergence.png";
  write_line_plot_png(path, plot, provenance);

  const Image image = read_png_cairo(path);
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 420);
  // The file holds exactly the rendered raster.
  const LinePlotRaster raster = render_line_plot(plot);
  ASSERT_EQ(image.pixels.size(), from_raster(raster).pixels.size());
  EXPECT_TRUE(image.pixels == from_raster(raster).pixels);
  EXPECT_EQ(read_png_text_chunks(path),
            (std::map<std::string, std::string>{{"obscura.provenance", provenance}}));
  // Without provenance, no text chunk at all.
  write_line_plot_png(dir_ / "bare.png", plot);
  EXPECT_TRUE(read_png_text_chunks(dir_ / "bare.png").empty());
  // Nothing but the two files: no temporaries left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "plots"), fs::directory_iterator()), 1);
}

TEST_F(LinePlotTest, FrameAndSeriesAreWhereTheDataAre) {
  LinePlot plot = simple_plot();
  plot.x.min = 0.0;
  plot.x.max = 10.0;
  plot.y.min = 0.0;
  plot.y.max = 1.0;
  // Three horizontal series over x in [2, 8], so columns outside must stay clear.
  const double levels[] = {0.2, 0.45, 0.7};
  plot.series = {horizontal("low", levels[0], 2, 8), horizontal("middle", levels[1], 2, 8),
                 horizontal("high", levels[2], 2, 8)};
  const fs::path path = dir_ / "levels.png";
  write_line_plot_png(path, plot);
  const Image image = read_png_cairo(path);
  const LinePlotRaster r = render_line_plot(plot);
  ASSERT_EQ(image.width, 900);
  ASSERT_EQ(image.height, 600);

  // The reported plot area is where the black frame is drawn: the frame lies
  // one pixel outside it, and the pixels just inside are not frame.
  const int left = static_cast<int>(r.plot_left), top = static_cast<int>(r.plot_top);
  const int right = static_cast<int>(r.plot_left + r.plot_width);
  const int bottom = static_cast<int>(r.plot_top + r.plot_height);
  const int mid_x = (left + right) / 2, mid_y = (top + bottom) / 2;
  const Rgb black{0, 0, 0};
  EXPECT_EQ(image.at(left - 1, mid_y), black);
  EXPECT_EQ(image.at(right, mid_y), black);
  EXPECT_EQ(image.at(mid_x, top - 1), black);
  EXPECT_EQ(image.at(mid_x, bottom), black);
  EXPECT_NE(image.at(left + 1, mid_y + 3), black);
  EXPECT_NE(image.at(mid_x + 3, bottom - 2), black);
  EXPECT_GT(r.plot_width, 0.7 * 900);  // the data get most of the canvas
  EXPECT_GT(r.plot_height, 0.7 * 600);
  EXPECT_DOUBLE_EQ(r.y_min, 0.0);  // explicit ranges used as given
  EXPECT_DOUBLE_EQ(r.x_max, 10.0);

  // Expected row of value v, from the axis range alone: a 2 px line centred
  // on the mapped coordinate covers the rows either side of it.
  auto column = [&](double x) { return static_cast<int>(left + x / 10.0 * (right - left)); };
  for (size_t k = 0; k < std::size(levels); ++k) {
    SCOPED_TRACE(k);
    const double expected = top + (1.0 - levels[k]) * (bottom - top) - 0.5;
    for (double x : {3.0, 5.0, 7.0}) {
      const std::vector<int> rows = rows_with(image, r, column(x), plot_series_rgb(k));
      ASSERT_FALSE(rows.empty()) << "x = " << x;
      for (int y : rows) EXPECT_NEAR(y, expected, 2.5) << "x = " << x;
    }
    // No data left of x = 2 or right of x = 8.
    EXPECT_TRUE(rows_with(image, r, column(1.0), plot_series_rgb(k)).empty());
    EXPECT_TRUE(rows_with(image, r, column(9.0), plot_series_rgb(k)).empty());
  }
  // The legend sits inside the plot area, away from the data, and shows a
  // sample of every series.
  EXPECT_GE(r.legend_left, r.plot_left);
  EXPECT_LE(r.legend_left + r.legend_width, r.plot_left + r.plot_width);
  EXPECT_GE(r.legend_top, r.plot_top);
  EXPECT_LE(r.legend_top + r.legend_height, r.plot_top + r.plot_height);
  for (size_t k = 0; k < std::size(levels); ++k) {
    int found = 0;
    for (int y = static_cast<int>(r.legend_top); y < r.legend_top + r.legend_height; ++y) {
      for (int x = static_cast<int>(r.legend_left); x < r.legend_left + r.legend_width; ++x)
        found += near(image.at(x, y), plot_series_rgb(k));
    }
    EXPECT_GT(found, 20) << "legend sample of series " << k;
  }
  // Tick labels: the explicit [0, 1] range gets 0.0 … 1.0 in steps of 0.2.
  EXPECT_EQ(r.y_ticks.major.front(), 0.0);
  EXPECT_EQ(r.y_ticks.major.back(), 1.0);
}

TEST_F(LinePlotTest, LogAxisPlacesValuesByDecade) {
  LinePlot plot = simple_plot();
  plot.y.log = true;
  plot.y.min = 1e-3;
  plot.y.max = 10.0;
  plot.series = {horizontal("a", 1e-2), horizontal("b", 1.0)};
  const LinePlotRaster r = render_line_plot(plot);
  const Image image = from_raster(r);
  EXPECT_EQ(r.y_ticks.major, (std::vector<double>{1e-3, 1e-2, 0.1, 1, 10}));
  const int x = static_cast<int>(r.plot_left + 0.3 * r.plot_width);
  // 1e-2 is one of four decades above the bottom, 1 three of four.
  for (auto [k, fraction] : {std::pair{0, 0.25}, std::pair{1, 0.75}}) {
    const double expected = r.plot_top + (1 - fraction) * r.plot_height - 0.5;
    const std::vector<int> rows = rows_with(image, r, x, plot_series_rgb(k));
    ASSERT_FALSE(rows.empty()) << k;
    for (int y : rows) EXPECT_NEAR(y, expected, 2.5) << k;
  }
}

TEST_F(LinePlotTest, NanAndInfPointsAreSkippedAndBreakTheLine) {
  LinePlot plot = simple_plot();
  plot.x.min = 0.0;
  plot.x.max = 10.0;
  PlotSeries s = horizontal("gappy", 0.5);  // x = 0, 1, ..., 10
  s.y[4] = kNaN;
  s.y[5] = kInf;
  s.x[6] = -kInf;
  plot.series = {s};
  const LinePlotRaster r = render_line_plot(plot);
  const Image image = from_raster(r);
  auto column = [&](double x) { return static_cast<int>(r.plot_left + x / 10 * r.plot_width); };
  const Rgb c = plot_series_rgb(0);
  EXPECT_FALSE(rows_with(image, r, column(2.0), c).empty());
  EXPECT_FALSE(rows_with(image, r, column(8.5), c).empty());
  // The gap spans x in (3, 7): no line across it.
  EXPECT_TRUE(rows_with(image, r, column(4.5), c).empty());
  EXPECT_TRUE(rows_with(image, r, column(5.5), c).empty());
  // The automatic y range comes from the finite points only.
  EXPECT_TRUE(std::isfinite(r.y_min) && std::isfinite(r.y_max));
  EXPECT_LT(r.y_min, 0.5);
  EXPECT_GT(r.y_max, 0.5);

  // A point alone between gaps is still drawn (as a dot).
  plot.series = {series("lonely", {1, 5, 9}, {kNaN, 0.5, kNaN})};
  const LinePlotRaster lonely = render_line_plot(plot);
  EXPECT_FALSE(rows_with(from_raster(lonely), lonely,
                         static_cast<int>(lonely.plot_left + 0.5 * lonely.plot_width), c)
                   .empty());
}

TEST_F(LinePlotTest, PointsFarOutsideAnExplicitRangeAreClipped) {
  // The diagonal y = x through [0, 1]², given by two points 1e9 ranges
  // outside it (~5e11 px): its visible part must be drawn where it belongs
  // (cairo's fixed point overflows on such coordinates and drops it).
  LinePlot plot = simple_plot();
  plot.x.min = plot.y.min = 0.0;
  plot.x.max = plot.y.max = 1.0;
  plot.series = {series("steep", {-1e9, 1e9}, {-1e9, 1e9})};
  const LinePlotRaster r = render_line_plot(plot);
  const Image image = from_raster(r);
  for (double v : {0.25, 0.5, 0.75}) {
    const int x = static_cast<int>(r.plot_left + v * r.plot_width);
    const double expected = r.plot_top + (1 - v) * r.plot_height - 0.5;
    const std::vector<int> rows = rows_with(image, r, x, plot_series_rgb(0));
    ASSERT_FALSE(rows.empty()) << v;
    for (int y : rows) EXPECT_NEAR(y, expected, 2.5) << v;
  }
}

TEST_F(LinePlotTest, HugeValuesOutsideTheRangeStillDrawTheirNeighbours) {
  // 1.7e308 maps to an infinite pixel coordinate unless pinned. The segments
  // to and from it must leave the plot straight up from their finite ends
  // (x = 0.2 and 0.8): over the plot's height they move ~1e-300 sideways.
  LinePlot plot = simple_plot();
  plot.x.min = plot.y.min = 0.0;
  plot.x.max = plot.y.max = 1.0;
  plot.series = {series("spike", {0.2, 0.5, 0.8}, {0.5, 1.7e308, 0.5})};
  const LinePlotRaster r = render_line_plot(plot);
  const Image image = from_raster(r);
  const Rgb c = plot_series_rgb(0);
  for (double x : {0.2, 0.8}) {
    // A 2 px line centred at px c covers [c - 1, c + 1], so column floor(c) fully.
    const int column = static_cast<int>(std::floor(r.plot_left + x * r.plot_width));
    const std::vector<int> rows = rows_with(image, r, column, c);
    SCOPED_TRACE(x);
    ASSERT_FALSE(rows.empty());
    // From the top of the plot down to y = 0.5, without a break.
    EXPECT_LE(rows.front(), r.plot_top + 1);
    EXPECT_NEAR(rows.back(), r.plot_top + 0.5 * r.plot_height, 3);
    EXPECT_GE(static_cast<double>(rows.size()), 0.5 * r.plot_height - 4);
  }
  // Nothing in between: the apex is far above the frame.
  EXPECT_TRUE(rows_with(image, r, static_cast<int>(r.plot_left + 0.5 * r.plot_width), c).empty());
}

TEST_F(LinePlotTest, LongSeriesHaveNoGaps) {
  // Long lines are stroked in pieces; no segment may go missing at a seam.
  LinePlot plot = simple_plot();
  plot.x.min = 0.0;
  plot.x.max = 1.0;
  PlotSeries s = series("long", {}, {});
  for (int i = 0; i <= 400; ++i) {
    s.x.push_back(i / 400.0);
    s.y.push_back(0.3 + 0.4 * (i % 2));  // a zigzag: every segment crosses y = 0.5
  }
  plot.series = {s};
  const LinePlotRaster r = render_line_plot(plot);
  const Image image = from_raster(r);
  for (int x = static_cast<int>(r.plot_left) + 2; x < r.plot_left + r.plot_width - 2; ++x) {
    ASSERT_FALSE(rows_with(image, r, x, plot_series_rgb(0)).empty()) << "column " << x;
  }
}

TEST_F(LinePlotTest, StylesDrawLinesMarkersOrBoth) {
  LinePlot plot = simple_plot();
  plot.x.min = 0.0;
  plot.x.max = 10.0;
  const std::vector<double> xs = {2, 8}, ys = {0.5, 0.5};
  auto at = [&](PlotSeries::Style style, double x) {
    plot.series = {series("s", xs, ys, style)};
    const LinePlotRaster r = render_line_plot(plot);
    return !rows_with(from_raster(r), r, static_cast<int>(r.plot_left + x / 10 * r.plot_width),
                      plot_series_rgb(0))
                .empty();
  };
  EXPECT_TRUE(at(PlotSeries::Style::kLine, 5));  // between the points
  EXPECT_FALSE(at(PlotSeries::Style::kMarkers, 5));
  EXPECT_TRUE(at(PlotSeries::Style::kMarkers, 2));  // at a point
  EXPECT_TRUE(at(PlotSeries::Style::kLineAndMarkers, 5));
  EXPECT_TRUE(at(PlotSeries::Style::kLineAndMarkers, 8));
}

TEST_F(LinePlotTest, AutomaticRangesHaveAMargin) {
  LinePlot plot = simple_plot();
  plot.series = {series("a", {0, 10}, {2, 4})};
  LinePlotRaster r = render_line_plot(plot);
  EXPECT_DOUBLE_EQ(r.x_min, -0.5);  // 5 % of the span each side
  EXPECT_DOUBLE_EQ(r.x_max, 10.5);
  EXPECT_DOUBLE_EQ(r.y_min, 1.9);
  EXPECT_DOUBLE_EQ(r.y_max, 4.1);
  // On a log axis the margin is in decades.
  plot.x.log = true;
  plot.series = {series("a", {1, 100}, {2, 4})};
  r = render_line_plot(plot);
  EXPECT_NEAR(std::log10(r.x_min), -0.1, 1e-12);
  EXPECT_NEAR(std::log10(r.x_max), 2.1, 1e-12);
  // One explicit end: the other from the data.
  plot.x.log = false;
  plot.y.min = 0.0;
  r = render_line_plot(plot);
  EXPECT_EQ(r.y_min, 0.0);
  EXPECT_DOUBLE_EQ(r.y_max, 4.2);
  // Constant data: a range around the value.
  plot.y.min.reset();
  plot.series = {series("flat", {1, 2, 3}, {7, 7, 7})};
  r = render_line_plot(plot);
  EXPECT_LT(r.y_min, 7);
  EXPECT_GT(r.y_max, 7);
  plot.series = {series("one point", {5}, {0})};
  r = render_line_plot(plot);
  EXPECT_LT(r.x_min, 5);
  EXPECT_GT(r.x_max, 5);
  EXPECT_LT(r.y_min, 0);
  EXPECT_GT(r.y_max, 0);
}

TEST_F(LinePlotTest, LegendAvoidsTheData) {
  // A diagonal from bottom left to top right: the top-right corner (the
  // default) would hide its end, the top-left and bottom-right are empty.
  LinePlot plot = simple_plot();
  plot.x.min = plot.y.min = 0.0;
  plot.x.max = plot.y.max = 1.0;
  PlotSeries diagonal = series("diagonal", {}, {});
  for (int i = 0; i <= 100; ++i) {
    diagonal.x.push_back(i / 100.0);
    diagonal.y.push_back(i / 100.0);
  }
  plot.series = {diagonal};
  const LinePlotRaster r = render_line_plot(plot);
  const double left = (r.legend_left - r.plot_left) / r.plot_width;
  const double right = (r.legend_left + r.legend_width - r.plot_left) / r.plot_width;
  const double top = 1 - (r.legend_top - r.plot_top) / r.plot_height;
  const double bottom = 1 - (r.legend_top + r.legend_height - r.plot_top) / r.plot_height;
  // The box [left, right] × [bottom, top] in data units misses the line y = x.
  EXPECT_TRUE(bottom > right || top < left)
      << "legend x " << left << ".." << right << ", y " << bottom << ".." << top;
}

TEST_F(LinePlotTest, SeriesWithoutPointsStaysInTheLegend) {
  LinePlot plot = simple_plot();
  plot.series.push_back(series("empty", {}, {}));
  plot.series.push_back(series("all NaN", {1, 2}, {kNaN, kNaN}));
  EXPECT_NO_THROW(write_line_plot_png(dir_ / "partly_empty.png", plot));
  EXPECT_TRUE(fs::exists(dir_ / "partly_empty.png"));
}

TEST_F(LinePlotTest, BadInputThrowsAndWritesNothing) {
  const fs::path path = dir_ / "bad.png";
  auto expect_error = [&](const LinePlot& plot, const std::string& says) {
    try {
      write_line_plot_png(path, plot);
      ADD_FAILURE() << "no error; expected one saying " << says;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path));
  };
  LinePlot plot = simple_plot();
  plot.series.clear();
  expect_error(plot, "no series");
  plot.series = {series("empty", {}, {}), series("nan", {kNaN, 1}, {1, kNaN})};
  expect_error(plot, "no series has a finite point");
  plot.series = {series("ragged", {1, 2, 3}, {1, 2})};
  expect_error(plot, "series 0 (\"ragged\") has 3 x values but 2 y values");
  plot.series = {series("", {1}, {1})};
  expect_error(plot, "series 0 has no label");
  // Log axes refuse non-positive values, naming the series, point and value.
  plot = simple_plot();
  plot.y.log = true;
  plot.series = {horizontal("fine", 1.0), series("decay", {1, 2, 3}, {0.5, 0.25, -0.125})};
  expect_error(plot, "series 1 (\"decay\") point 2 has y = -0.125");
  plot.y.log = false;
  plot.x.log = true;
  plot.series = {series("at zero", {0, 1}, {1, 2})};
  expect_error(plot, "point 0 has x = 0");
  plot.x.min = 1.0;
  plot.x.log = false;
  plot.x.max = 1.0;
  expect_error(plot, "x axis: empty range");
  plot.x.max = kNaN;
  expect_error(plot, "x axis: invalid");
  plot = simple_plot();
  plot.y.min = 2.0;  // above every data point, and no max
  expect_error(plot, "y axis: empty range");
  plot = simple_plot();
  plot.y.log = true;
  plot.y.min = -1.0;
  expect_error(plot, "y axis: invalid logarithmic limit");
  plot = simple_plot();
  plot.width_px = 100;
  expect_error(plot, "canvas");
  plot = simple_plot();
  for (int k = 0; k < 40; ++k) plot.series.push_back(horizontal("series " + std::to_string(k), k));
  expect_error(plot, "legend");
  EXPECT_THROW(write_line_plot_png(path, simple_plot(), std::string("a\0b", 3)), Error);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir_));  // no temporary files either
}

TEST_F(LinePlotTest, FailedWriteLeavesNoFile) {
  // An old plot survives a failed rewrite untouched.
  const fs::path path = dir_ / "plot.png";
  write_line_plot_png(path, simple_plot());
  std::ifstream before_file(path, std::ios::binary);
  const std::string before((std::istreambuf_iterator<char>(before_file)), {});
  LinePlot bad = simple_plot();
  bad.series[0].label.clear();
  EXPECT_THROW(write_line_plot_png(path, bad), Error);
  std::ifstream after_file(path, std::ios::binary);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after_file)), {}), before);

  // A failure after the whole image is encoded (the final rename onto a
  // non-empty directory fails) leaves neither the file nor its temporary.
  const fs::path blocked = dir_ / "blocked" / "plot.png";
  fs::create_directories(blocked / "occupied");
  EXPECT_THROW(write_line_plot_png(blocked, simple_plot()), Error);
  EXPECT_TRUE(fs::is_directory(blocked));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "blocked"), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace obscura
