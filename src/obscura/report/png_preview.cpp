#include "obscura/report/png_preview.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
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

// Layout, px (font sizes in cairo user units = px on an image surface).
constexpr int kMargin = 12;
constexpr int kBarGap = 16;  // image to colour bar
constexpr int kBarWidth = 18;
constexpr int kTickLength = 4;
constexpr int kLabelGap = 3;             // tick mark to its label
constexpr int kUnitsGap = 8;             // tick labels to the units label
constexpr int kTitleGap = 8;             // title line to the image
constexpr int kTargetImageHeight = 256;  // small images are upscaled to at least this
constexpr int kMaxImageWidth = 4096;     // ...unless that would make them absurdly wide
constexpr int kTickCount = 5;
constexpr double kTitleFontSize = 15;
constexpr double kTickFontSize = 12;
constexpr double kUnitsFontSize = 13;
constexpr std::uint8_t kNanGrey = 128;

// 16 evenly spaced samples (entries 0, 17, ..., 255) of matplotlib's "inferno"
// (van der Walt & Smith, CC0; lib/matplotlib/_cm_listed.py), interpolated
// linearly: the largest difference from the 256-entry table is far below
// what a preview needs.
constexpr float kInferno[16][3] = {
    {0.001462f, 0.000466f, 0.013866f}, {0.046915f, 0.030324f, 0.150164f},
    {0.142378f, 0.046242f, 0.308553f}, {0.258234f, 0.038571f, 0.406485f},
    {0.366529f, 0.071579f, 0.431994f}, {0.472328f, 0.110547f, 0.428334f},
    {0.578304f, 0.148039f, 0.404411f}, {0.682656f, 0.189501f, 0.360757f},
    {0.780517f, 0.243327f, 0.299523f}, {0.865006f, 0.316822f, 0.226055f},
    {0.929644f, 0.411479f, 0.145367f}, {0.970919f, 0.522853f, 0.058367f},
    {0.987622f, 0.645320f, 0.039886f}, {0.978806f, 0.774545f, 0.176037f},
    {0.950018f, 0.903409f, 0.380271f}, {0.988362f, 0.998364f, 0.644924f},
};

std::uint8_t to_byte(double c) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

using cairo_canvas::CairoPtr;
using cairo_canvas::font_extents;
using cairo_canvas::set_font;
using cairo_canvas::SurfacePtr;
using cairo_canvas::text_advance;

void validate_image(const std::string& file, int width, int height,
                    const std::vector<float>& values) {
  if (width <= 0 || height <= 0) {
    throw InputError(file, "",
                     fmt::format("image size must be positive, got {}x{}", width, height));
  }
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (values.size() != count) {
    throw InputError(file, "values",
                     fmt::format("image has {} pixels, expected {}x{} = {}", values.size(), width,
                                 height, count));
  }
}

// The colour bar range: the options where given, else the finite data range.
std::pair<double, double> value_range(const std::string& file, const std::vector<float>& values,
                                      const PreviewOptions& options) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (float v : values) {
    if (std::isfinite(v)) {
      lo = std::min(lo, static_cast<double>(v));
      hi = std::max(hi, static_cast<double>(v));
    }
  }
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;  // no finite pixel at all
  if (options.min) lo = *options.min;
  if (options.max) hi = *options.max;
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    throw InputError(file, "min/max", fmt::format("invalid colour range [{}, {}]", lo, hi));
  }
  if (lo == hi) {
    // A constant image: a tiny range around the value keeps the mapping
    // defined (no 0/0) and paints the image in the middle of the bar.
    const double half = lo != 0.0 ? std::abs(lo) * 1e-6 : 1e-6;
    lo -= half;
    hi += half;
  }
  return {lo, hi};
}

// Colour bar ticks as (fraction of the bar from the bottom, label).
std::vector<std::pair<double, std::string>> bar_ticks(double min, double max) {
  const double span = max - min;
  std::vector<std::pair<double, std::string>> ticks;
  for (int i = 0; i < kTickCount; ++i) {
    const double fraction = static_cast<double>(i) / (kTickCount - 1);
    ticks.emplace_back(fraction, fmt::format("{:.4g}", min + span * fraction));
  }
  // A constant image (or a very narrow range) would repeat one label five
  // times; a single label in the middle says the same without the clutter.
  if (ticks.front().second == ticks.back().second) ticks = {ticks[kTickCount / 2]};
  return ticks;
}

// Where the parts of a preview go, px, and the fonts they are set in.
struct PreviewLayout {
  cairo_font_extents_t title_font, tick_font, units_font;
  int image_w = 0, image_h = 0;  // the upscaled image
  int bar_x = 0, label_x = 0, units_x = 0;
  double units_len = 0;  // length of the units label along the bar
};

// Measures the text on a scratch surface to size the canvas: sets the
// canvas size and the image position in `out`.
PreviewLayout lay_out(const PreviewOptions& options,
                      const std::vector<std::pair<double, std::string>>& ticks, int image_w,
                      int image_h, PreviewRaster& out) {
  PreviewLayout l;
  l.image_w = image_w;
  l.image_h = image_h;
  SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
  CairoPtr measure(cairo_create(scratch.get()));
  set_font(measure.get(), kTitleFontSize);
  l.title_font = font_extents(measure.get());
  const double title_w = options.title.empty() ? 0 : text_advance(measure.get(), options.title);
  const int title_h =
      options.title.empty() ? 0 : static_cast<int>(std::ceil(l.title_font.height)) + kTitleGap;
  set_font(measure.get(), kTickFontSize);
  l.tick_font = font_extents(measure.get());
  double label_w = 0;
  for (const auto& tick : ticks)
    label_w = std::max(label_w, text_advance(measure.get(), tick.second));
  set_font(measure.get(), kUnitsFontSize);
  l.units_font = font_extents(measure.get());
  l.units_len = options.units.empty() ? 0 : text_advance(measure.get(), options.units);
  const int units_thickness =
      options.units.empty() ? 0 : static_cast<int>(std::ceil(l.units_font.height));

  out.image_x = kMargin;
  out.image_y = kMargin + title_h;
  l.bar_x = out.image_x + image_w + kBarGap;
  l.label_x = l.bar_x + kBarWidth + kTickLength + kLabelGap;
  l.units_x = l.label_x + static_cast<int>(std::ceil(label_w)) + kUnitsGap;
  out.width = std::max(l.units_x + units_thickness + kMargin,
                       2 * kMargin + static_cast<int>(std::ceil(title_w)));
  out.height = out.image_y + image_h + kMargin;
  return l;
}

// Pixels are written straight into the surface: nearest-neighbour upscale
// and the colour bar need no resampling, and this avoids cairo filtering.
void paint_image_and_bar(cairo_surface_t* surface, int width, const std::vector<float>& values,
                         const PreviewOptions& options, const PreviewLayout& l,
                         const PreviewRaster& out) {
  const double span = out.max - out.min;
  const cairo_canvas::PixelWriter canvas(surface);
  auto put = [&](int x, int y, std::array<std::uint8_t, 3> c) { canvas.put(x, y, c); };
  for (int y = 0; y < l.image_h; ++y) {
    const float* row = values.data() + static_cast<size_t>(y / out.scale) * width;
    for (int x = 0; x < l.image_w; ++x) {
      const float v = row[x / out.scale];
      put(out.image_x + x, out.image_y + y,
          std::isnan(v) ? std::array<std::uint8_t, 3>{kNanGrey, kNanGrey, kNanGrey}
                        : colormap_rgb(options.colormap, (v - out.min) / span));
    }
  }
  for (int y = 0; y < l.image_h; ++y) {
    const auto c = colormap_rgb(options.colormap, 1.0 - (y + 0.5) / l.image_h);
    for (int x = 0; x < kBarWidth; ++x) put(l.bar_x + x, out.image_y + y, c);
  }
  cairo_surface_mark_dirty(surface);
}

// Bar frame, ticks and labels, the title, and the units beside the bar.
// Lines sit on half-pixel coordinates so a 1 px stroke covers exactly one
// pixel column/row.
void draw_texts(cairo_t* cr, const PreviewOptions& options,
                const std::vector<std::pair<double, std::string>>& ticks, const PreviewLayout& l,
                const PreviewRaster& out) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, l.bar_x - 0.5, out.image_y - 0.5, kBarWidth + 1, l.image_h + 1);
  cairo_stroke(cr);
  set_font(cr, kTickFontSize);
  for (const auto& [fraction, label] : ticks) {
    const double y = out.image_y + l.image_h * (1.0 - fraction);
    const double line_y = std::floor(y) + 0.5;
    cairo_move_to(cr, l.bar_x + kBarWidth + 0.5, line_y);
    cairo_line_to(cr, l.bar_x + kBarWidth + 0.5 + kTickLength, line_y);
    cairo_stroke(cr);
    cairo_move_to(cr, l.label_x, y + (l.tick_font.ascent - l.tick_font.descent) / 2);
    cairo_show_text(cr, label.c_str());
  }
  if (!options.title.empty()) {
    set_font(cr, kTitleFontSize);
    cairo_move_to(cr, kMargin, kMargin + l.title_font.ascent);
    cairo_show_text(cr, options.title.c_str());
  }
  if (!options.units.empty()) {
    // Rotated to read bottom to top beside the bar; after rotate(-pi/2) the
    // glyphs' ascent points left, so the baseline sits `ascent` right of units_x.
    set_font(cr, kUnitsFontSize);
    cairo_save(cr);
    cairo_translate(cr, l.units_x + l.units_font.ascent,
                    out.image_y + (l.image_h + l.units_len) / 2);
    cairo_rotate(cr, -std::numbers::pi / 2);
    cairo_move_to(cr, 0, 0);
    cairo_show_text(cr, options.units.c_str());
    cairo_restore(cr);
  }
}

PreviewRaster render(const std::string& file, int width, int height,
                     const std::vector<float>& values, const PreviewOptions& options) {
  validate_image(file, width, height, values);
  PreviewRaster out;
  std::tie(out.min, out.max) = value_range(file, values, options);
  out.scale =
      std::max(1, std::min((kTargetImageHeight + height - 1) / height, kMaxImageWidth / width));
  const auto ticks = bar_ticks(out.min, out.max);
  const PreviewLayout layout = lay_out(options, ticks, width * out.scale, height * out.scale, out);

  SurfacePtr surface = cairo_canvas::create_surface(out.width, out.height, /*white=*/true);
  CairoPtr cr(cairo_create(surface.get()));
  paint_image_and_bar(surface.get(), width, values, options, layout, out);
  draw_texts(cr.get(), options, ticks, layout, out);
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("cairo: drawing the preview failed: {}",
                            cairo_status_to_string(cairo_status(cr.get()))));
  }
  cairo_surface_flush(surface.get());
  out.rgb = cairo_canvas::surface_rgb(surface.get());
  return out;
}

}  // namespace

std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t) {
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  if (map == Colormap::kGray) {
    const std::uint8_t g = to_byte(t);
    return {g, g, g};
  }
  const double x = t * 15.0;
  const int i = std::min(static_cast<int>(x), 14);
  const double f = x - i;
  std::array<std::uint8_t, 3> rgb;
  for (int c = 0; c < 3; ++c)
    rgb[c] = to_byte(kInferno[i][c] + f * (kInferno[i + 1][c] - kInferno[i][c]));
  return rgb;
}

PreviewRaster render_preview(int width, int height, const std::vector<float>& values,
                             const PreviewOptions& options) {
  return render("", width, height, values, options);
}

void write_png_preview(const std::filesystem::path& path, int width, int height,
                       const std::vector<float>& values, const PreviewOptions& options,
                       const std::map<std::string, std::string>& text_chunks) {
  const std::string file = path.string();
  const PreviewRaster raster = render(file, width, height, values, options);

  write_rgb_png(path, raster.width, raster.height, raster.rgb, text_chunks);
}

}  // namespace obscura
