#pragma once
// A quick-look PNG of one scalar image for a human: the image (nearest-neighbour
// upscaled), a title, and a vertical colour bar with tick labels and units.
// Numbers for analysis belong in the EXR; the PNG carries the same provenance
// as text chunks so a preview found on its own can still be traced.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "obscura/io/png_file.h"

namespace obscura {

enum class Colormap { kInferno, kGray };

// sRGB 8-bit colour of `t` in [0, 1] (clamped) under `map`.
std::array<std::uint8_t, 3> colormap_rgb(Colormap map, double t);

struct PreviewOptions {
  std::string title;  // e.g. "ir / lwir band radiance"
  std::string units;  // UTF-8, e.g. "W m⁻² sr⁻¹"
  // Colour bar range, in the data's units; by default the finite min / max.
  std::optional<double> min, max;
  Colormap colormap = Colormap::kInferno;
};

// The rendered preview before PNG encoding (exposed for tests).
struct PreviewRaster {
  int width = 0, height = 0;      // canvas size, px
  std::vector<std::uint8_t> rgb;  // 3 bytes per px, row-major, top row first
  int image_x = 0, image_y = 0;   // top-left of the data image on the canvas, px
  int scale = 1;                  // integer upscale of each data pixel
  double min = 0, max = 0;        // colour bar range actually used
};

// Renders `values` (width*height, row-major, top row first). NaN pixels are
// mid-grey; ±inf clamp to the ends of the bar. Throws InputError on a bad
// size or range.
PreviewRaster render_preview(int width, int height, const std::vector<float>& values,
                             const PreviewOptions& options);

// Renders and writes a PNG through an AtomicFile. `text_chunks` (keyword ->
// value) are stored as tEXt, or iTXt when the value is not plain ASCII;
// keywords must be 1-79 printable ASCII characters.
void write_png_preview(const std::filesystem::path& path, int width, int height,
                       const std::vector<float>& values, const PreviewOptions& options,
                       const std::map<std::string, std::string>& text_chunks);

}  // namespace obscura
