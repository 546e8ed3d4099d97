#pragma once
// PNG files: an 8-bit RGB image with text chunks, written atomically (the file
// appears complete or not at all), and the readers the tests use. One libpng
// wrapper for every PNG obscura writes (previews, line plots).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace obscura {

// Writes width × height pixels of row-major RGB bytes. `text_chunks`
// (keyword -> value) are stored before the image data as tEXt, or iTXt when
// the value is not plain ASCII; keywords must be 1-79 printable ASCII
// characters and values must hold no NUL (InputError otherwise). Throws Error
// on an I/O or libpng failure, leaving no file.
void write_rgb_png(const std::filesystem::path& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb,
                   const std::map<std::string, std::string>& text_chunks);

// Readers, mainly for tests. Throw InputError if the file is not a readable PNG.
std::map<std::string, std::string> read_png_text_chunks(const std::filesystem::path& path);
struct PngSize {
  int width = 0, height = 0;  // px
};
PngSize read_png_size(const std::filesystem::path& path);

}  // namespace obscura
