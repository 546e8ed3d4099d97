#pragma once
// Small helpers shared by the cairo drawings obscura writes (image previews,
// line plots): owning pointers, the one font, text metrics, and the copy of an
// opaque ARGB32 surface into packed RGB bytes.
#include <cairo.h>
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "obscura/core/error.h"

namespace obscura::cairo_canvas {

inline constexpr const char* kFontFamily = "DejaVu Sans";  // fonts-dejavu-core

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using CairoPtr = std::unique_ptr<cairo_t, ContextDeleter>;

// An ARGB32 image surface of width × height px; throws Error if cairo cannot
// make one (e.g. too large). `white`: painted opaque white.
inline SurfacePtr create_surface(int width, int height, bool white = false) {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw Error(fmt::format("cairo: cannot create a {}x{} surface: {}", width, height,
                            cairo_status_to_string(cairo_surface_status(surface.get()))));
  if (white) {
    CairoPtr cr(cairo_create(surface.get()));
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_paint(cr.get());
  }
  return surface;
}

// Writes opaque sRGB pixels straight into an ARGB32 surface, for images that
// need no resampling or filtering by cairo. Call cairo_surface_mark_dirty()
// before drawing on the surface with cairo again.
class PixelWriter {
 public:
  // Flushes `surface` (pending cairo drawing lands first).
  explicit PixelWriter(cairo_surface_t* surface)
      : data_((cairo_surface_flush(surface), cairo_image_surface_get_data(surface))),
        stride_(cairo_image_surface_get_stride(surface)) {}
  void put(int x, int y, std::array<std::uint8_t, 3> c) const {
    // ARGB32 is a native-endian uint32 with alpha in the top byte; opaque, so
    // premultiplication changes nothing.
    const std::uint32_t argb = 0xff000000u | (std::uint32_t{c[0]} << 16) |
                               (std::uint32_t{c[1]} << 8) | std::uint32_t{c[2]};
    std::memcpy(data_ + static_cast<std::size_t>(y) * stride_ + static_cast<std::size_t>(x) * 4,
                &argb, 4);
  }

 private:
  unsigned char* data_;
  int stride_;
};

inline void set_font(cairo_t* cr, double size) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

inline double text_advance(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

inline cairo_font_extents_t font_extents(cairo_t* cr) {
  cairo_font_extents_t extents;
  cairo_font_extents(cr, &extents);
  return extents;
}

// Row-major RGB bytes of a flushed ARGB32 surface. ARGB32 is a native-endian
// uint32 with alpha on top; the canvases are opaque, so premultiplication
// changes nothing.
inline std::vector<std::uint8_t> surface_rgb(cairo_surface_t* surface) {
  const int width = cairo_image_surface_get_width(surface),
            height = cairo_image_surface_get_height(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t argb;
      std::memcpy(&argb,
                  data + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x) * 4, 4);
      std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      p[0] = static_cast<std::uint8_t>(argb >> 16);
      p[1] = static_cast<std::uint8_t>(argb >> 8);
      p[2] = static_cast<std::uint8_t>(argb);
    }
  return rgb;
}

}  // namespace obscura::cairo_canvas
