#include "obscura/io/envi_cube.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"

namespace obscura {
namespace {

// Braces and commas delimit ENVI lists: a name must not carry them.
std::string list_item(std::string s) {
  for (char& c : s)
    if (c == '{' || c == '}' || c == ',' || c == '\n') c = '_';
  return s;
}

template <class F>
std::string list(const std::vector<EnviBand>& bands, F item) {
  std::string s = "{";
  for (std::size_t i = 0; i < bands.size(); ++i) s += (i ? ", " : "") + item(bands[i]);
  return s + "}";
}

// A free-text field in braces: only braces and line breaks would end it.
std::string text_field(std::string s) {
  for (char& c : s)
    if (c == '{' || c == '}' || c == '\n') c = '_';
  return s;
}

}  // namespace

std::string envi_header_text(const EnviCube& cube) {
  // data type 4: 32-bit float; byte order 0: little-endian; interleave bsq:
  // every band's whole image, one after the other.
  return fmt::format(
      "ENVI\n"
      "description = {{{}}}\n"
      "samples = {}\n"
      "lines = {}\n"
      "bands = {}\n"
      "header offset = 0\n"
      "file type = ENVI Standard\n"
      "data type = 4\n"
      "interleave = bsq\n"
      "byte order = 0\n"
      "band names = {}\n"
      "wavelength units = Micrometers\n"
      "wavelength = {}\n"
      "fwhm = {}\n"
      "data units = {}\n",
      text_field(cube.description), cube.width, cube.height, cube.bands.size(),
      list(cube.bands, [](const EnviBand& b) { return list_item(b.name); }),
      list(cube.bands, [](const EnviBand& b) { return fmt::format("{:.9g}", b.centre_um); }),
      list(cube.bands, [](const EnviBand& b) { return fmt::format("{:.9g}", b.width_um); }),
      cube.data_units);
}

std::vector<std::filesystem::path> write_envi_cube(const std::filesystem::path& img_path,
                                                   const EnviCube& cube) {
  if (cube.bands.empty() || cube.width <= 0 || cube.height <= 0)
    throw InputError(img_path.string(), "", "an ENVI cube needs at least one band and one pixel");
  static_assert(std::endian::native == std::endian::little,
                "the cube is written as the machine's floats, declared little-endian");
  const std::size_t pixels =
      static_cast<std::size_t>(cube.width) * static_cast<std::size_t>(cube.height);
  std::string bytes(pixels * sizeof(float) * cube.bands.size(), '\0');
  for (std::size_t b = 0; b < cube.bands.size(); ++b)
    std::memcpy(bytes.data() + b * pixels * sizeof(float), cube.bands[b].values,
                pixels * sizeof(float));
  std::filesystem::path hdr_path = img_path;
  hdr_path.replace_extension(".hdr");
  write_text_file_atomic(img_path, bytes);
  write_text_file_atomic(hdr_path, envi_header_text(cube));
  return {img_path, hdr_path};
}

}  // namespace obscura
