#include "obscura/film/sensor_image_rows.h"

#include <algorithm>
#include <cstdint>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"

namespace obscura {
namespace {

// One per-pixel array's share: whether the image has it, then its rows.
template <class T>
void put_rows(ByteWriter& out, const std::vector<T>& pixels, int width, int height, int offset,
              int stride) {
  out.put<std::uint8_t>(pixels.empty() ? 0 : 1);
  if (pixels.empty()) return;
  std::vector<T> rows;
  for (int y = offset; y < height; y += stride)
    rows.insert(rows.end(), pixels.begin() + static_cast<std::ptrdiff_t>(y) * width,
                pixels.begin() + static_cast<std::ptrdiff_t>(y + 1) * width);
  out.put_vector(rows);
}

template <class T>
void get_rows(ByteReader& in, std::vector<T>& pixels, int width, int height, int offset,
              int stride) {
  const bool present = in.get<std::uint8_t>() != 0;
  OBSCURA_CHECK_MSG(present == !pixels.empty(), "image share of another kind of image");
  if (!present) return;
  const std::vector<T> rows = in.get_vector<T>();
  std::size_t at = 0;
  for (int y = offset; y < height; y += stride, at += static_cast<std::size_t>(width)) {
    OBSCURA_CHECK_MSG(at + static_cast<std::size_t>(width) <= rows.size(),
                      "image share with fewer rows than its shape");
    std::copy(rows.begin() + static_cast<std::ptrdiff_t>(at),
              rows.begin() + static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(width)),
              pixels.begin() + static_cast<std::ptrdiff_t>(y) * width);
  }
  OBSCURA_CHECK_MSG(at == rows.size(), "image share with more rows than its shape");
}

}  // namespace

std::string encode_image_rows(const SensorImage& image, int row_offset, int row_stride) {
  OBSCURA_CHECK(row_stride >= 1 && row_offset >= 0 && row_offset < row_stride);
  const int w = image.width, h = image.height;
  ByteWriter out;
  out.put<std::int32_t>(w);
  out.put<std::int32_t>(h);
  out.put<std::int32_t>(row_offset);
  out.put<std::int32_t>(row_stride);
  out.put<std::uint64_t>(image.bands.size());
  for (const BandImage& b : image.bands) {
    put_rows(out, b.radiance, w, h, row_offset, row_stride);
    put_rows(out, b.transmittance, w, h, row_offset, row_stride);
    put_rows(out, b.apparent_temperature, w, h, row_offset, row_stride);
    put_rows(out, b.radiance_stderr, w, h, row_offset, row_stride);
  }
  put_rows(out, image.samples_per_pixel, w, h, row_offset, row_stride);
  out.put(image.stats.rays);
  out.put(image.stats.segments);
  out.put(image.stats.integrand_evals);
  return out.take();
}

void decode_image_rows(const std::string& bytes, SensorImage& image) {
  ByteReader in(bytes);
  const int w = in.get<std::int32_t>(), h = in.get<std::int32_t>();
  const int offset = in.get<std::int32_t>(), stride = in.get<std::int32_t>();
  OBSCURA_CHECK_MSG(w == image.width && h == image.height, "image share of another size");
  OBSCURA_CHECK(stride >= 1 && offset >= 0 && offset < stride);
  OBSCURA_CHECK_MSG(in.get<std::uint64_t>() == image.bands.size(),
                    "image share with another number of bands");
  for (BandImage& b : image.bands) {
    get_rows(in, b.radiance, w, h, offset, stride);
    get_rows(in, b.transmittance, w, h, offset, stride);
    get_rows(in, b.apparent_temperature, w, h, offset, stride);
    get_rows(in, b.radiance_stderr, w, h, offset, stride);
  }
  get_rows(in, image.samples_per_pixel, w, h, offset, stride);
  image.stats.rays += in.get<std::uint64_t>();
  image.stats.segments += in.get<std::uint64_t>();
  image.stats.integrand_evals += in.get<std::uint64_t>();
  OBSCURA_CHECK(in.done());
}

}  // namespace obscura
