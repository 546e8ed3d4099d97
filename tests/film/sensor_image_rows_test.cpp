// Shares of a SensorImage's rows (film/sensor_image_rows.h): the shares of N
// processes put together are the image, bit for bit; a share of another shape
// is refused.
#include "obscura/film/sensor_image_rows.h"

#include <gtest/gtest.h>

#include "obscura/core/check.h"

namespace obscura {
namespace {

SensorImage image(int w, int h, bool with_stderr, float scale) {
  SensorImage im;
  im.sensor = "ir";
  im.width = w;
  im.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  BandImage b;
  b.band = Band::preset("lwir");
  for (std::size_t i = 0; i < n; ++i) {
    b.radiance.push_back(scale * (1.0f + i));
    b.transmittance.push_back(0.5f / (1 + i));
    b.apparent_temperature.push_back(250.0f + i);
    if (with_stderr) b.radiance_stderr.push_back(0.01f * i);
  }
  im.bands = {b, b};
  im.samples_per_pixel.assign(n, 4);
  im.stats.rays = 10;
  return im;
}

// Only the rows of one share kept, the rest zero, as a rank renders them.
SensorImage share(const SensorImage& full, int offset, int stride) {
  SensorImage s = full;
  for (int y = 0; y < full.height; ++y) {
    if (y % stride == offset) continue;
    for (BandImage& b : s.bands)
      for (auto* v : {&b.radiance, &b.transmittance, &b.apparent_temperature, &b.radiance_stderr})
        if (!v->empty())
          std::fill(v->begin() + y * full.width, v->begin() + (y + 1) * full.width, 0.0f);
    std::fill(s.samples_per_pixel.begin() + y * full.width,
              s.samples_per_pixel.begin() + (y + 1) * full.width, 0u);
  }
  return s;
}

TEST(SensorImageRows, SharesOfThreeRanksMakeTheWholeImage) {
  for (bool with_stderr : {false, true}) {
    const SensorImage full = image(5, 7, with_stderr, 1.5f);
    SensorImage merged = share(full, 0, 3);
    for (int r = 1; r < 3; ++r)
      decode_image_rows(encode_image_rows(share(full, r, 3), r, 3), merged);
    for (std::size_t b = 0; b < full.bands.size(); ++b) {
      EXPECT_EQ(merged.bands[b].radiance, full.bands[b].radiance);
      EXPECT_EQ(merged.bands[b].transmittance, full.bands[b].transmittance);
      EXPECT_EQ(merged.bands[b].apparent_temperature, full.bands[b].apparent_temperature);
      EXPECT_EQ(merged.bands[b].radiance_stderr, full.bands[b].radiance_stderr);
    }
    EXPECT_EQ(merged.samples_per_pixel, full.samples_per_pixel);
    EXPECT_EQ(merged.stats.rays, 30u) << "each share's rays added";
  }
}

TEST(SensorImageRows, AShareWithMoreRanksThanRowsIsEmptyAndFine) {
  const SensorImage full = image(3, 2, false, 1.0f);
  SensorImage target = full;
  decode_image_rows(encode_image_rows(full, 3, 4), target);  // rows 3, 7, …: none
  EXPECT_EQ(target.bands[0].radiance, full.bands[0].radiance);
}

TEST(SensorImageRows, AShareOfAnotherShapeIsRefused) {
  const std::string bytes = encode_image_rows(image(5, 7, true, 1.0f), 0, 2);
  SensorImage other = image(5, 8, true, 1.0f);
  EXPECT_THROW(decode_image_rows(bytes, other), InternalError);
  SensorImage no_stderr = image(5, 7, false, 1.0f);
  EXPECT_THROW(decode_image_rows(bytes, no_stderr), InternalError);
}

}  // namespace
}  // namespace obscura
