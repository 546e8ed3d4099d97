#include "obscura/io/png_file.h"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"

namespace obscura {
namespace {

// ---- libpng --------------------------------------------------------------
// libpng reports errors by longjmp. The functions that call setjmp hold only
// trivially destructible locals, set before setjmp and never changed after,
// so the jump skips no destructor and reads no indeterminate variable.

struct PngErrorState {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", message);
  std::longjmp(png_jmpbuf(png), 1);
}

void on_png_warning(png_structp, png_const_charp) {}

bool encode_png(std::FILE* file, int width, int height, png_bytep* rows, png_textp texts,
                int text_count, PngErrorState* error) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // Text before IDAT, so readers that stop at the image data still see it.
  if (text_count > 0) png_set_text(png, info, texts, text_count);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// Reads the header, and with `whole` the entire file (so text chunks after
// IDAT are seen too); copies the text chunks into `texts` when non-null.
bool decode_png(std::FILE* file, bool whole, png_uint_32* width, png_uint_32* height,
                std::map<std::string, std::string>* texts, PngErrorState* error) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  if (whole) {
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  } else {
    png_read_info(png, info);
  }
  *width = png_get_image_width(png, info);
  *height = png_get_image_height(png, info);
  if (texts != nullptr) {
    png_textp text = nullptr;
    int count = 0;
    png_get_text(png, info, &text, &count);
    try {
      for (int i = 0; i < count; ++i) {
        const size_t length = text[i].compression == PNG_ITXT_COMPRESSION_NONE ||
                                      text[i].compression == PNG_ITXT_COMPRESSION_zTXt
                                  ? text[i].itxt_length
                                  : text[i].text_length;
        (*texts)[text[i].key] = std::string(text[i].text, length);
      }
    } catch (...) {
      png_destroy_read_struct(&png, &info, nullptr);
      throw;
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

bool is_ascii(const std::string& s) {
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

void validate_text_chunks(const std::string& file,
                          const std::map<std::string, std::string>& chunks) {
  for (const auto& [key, value] : chunks) {
    // PNG spec §11.3.4.2: keywords are 1-79 Latin-1 characters; we allow
    // printable ASCII only, which every reader decodes the same way.
    const bool printable =
        std::all_of(key.begin(), key.end(), [](char c) { return c >= 32 && c <= 126; });
    if (key.empty() || key.size() > 79 || !printable) {
      throw InputError(file, key, "PNG text keyword must be 1-79 printable ASCII characters");
    }
    if (value.find('\0') != std::string::npos) {
      throw InputError(file, key, "PNG text value contains a NUL byte");
    }
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::map<std::string, std::string> read_png(const std::filesystem::path& path, bool whole,
                                            PngSize* size) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    throw InputError(path.string(), "", std::string("cannot read file: ") + std::strerror(errno));
  }
  std::map<std::string, std::string> texts;
  png_uint_32 width = 0, height = 0;
  PngErrorState error;
  if (!decode_png(file.get(), whole, &width, &height, whole ? &texts : nullptr, &error)) {
    throw InputError(path.string(), "", std::string("cannot read PNG: ") + error.message);
  }
  if (size != nullptr) *size = {static_cast<int>(width), static_cast<int>(height)};
  return texts;
}

}  // namespace

void write_rgb_png(const std::filesystem::path& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb,
                   const std::map<std::string, std::string>& text_chunks) {
  const std::string file = path.string();
  validate_text_chunks(file, text_chunks);
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * height * 3)
    throw Error(fmt::format(
        "cannot write PNG {}: {}×{} pixels need {} bytes of RGB, got {}", file, width, height,
        static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0) * 3, rgb.size()));
  // libpng wants mutable char* for keys and values; these copies outlive the write.
  std::vector<std::string> strings;
  strings.reserve(2 * text_chunks.size());
  std::vector<png_text> texts(text_chunks.size());
  size_t n = 0;
  for (const auto& [key, value] : text_chunks) {
    png_text& t = texts[n++];
    std::memset(&t, 0, sizeof t);
    t.key = strings.emplace_back(key).data();
    t.text = strings.emplace_back(value).data();
    // tEXt is Latin-1, so anything beyond ASCII (UTF-8 units, paths) goes in iTXt.
    t.compression = is_ascii(value) ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
  }
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[y] = const_cast<png_bytep>(rgb.data() + static_cast<size_t>(y) * width * 3);

  AtomicFile out(path);
  std::FILE* f = std::fopen(out.temp_path().c_str(), "wb");
  if (f == nullptr) {
    throw Error(fmt::format("cannot open {}: {}", out.temp_path().string(), std::strerror(errno)));
  }
  PngErrorState error;
  const bool ok = encode_png(f, width, height, rows.data(), texts.data(),
                             static_cast<int>(texts.size()), &error);
  const bool write_failed = std::ferror(f) != 0;
  const bool close_failed = std::fclose(f) != 0;
  if (!ok) throw Error(fmt::format("cannot write PNG {}: {}", file, error.message));
  if (write_failed || close_failed) {
    throw Error(fmt::format("cannot write PNG {}: {}", file, std::strerror(errno)));
  }
  out.commit();
}

std::map<std::string, std::string> read_png_text_chunks(const std::filesystem::path& path) {
  return read_png(path, /*whole=*/true, nullptr);
}

PngSize read_png_size(const std::filesystem::path& path) {
  PngSize size;
  read_png(path, /*whole=*/false, &size);
  return size;
}

}  // namespace obscura
