#include "obscura/report/png_preview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "obscura/core/error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class PngPreviewTest : public testing::TempDirTest {};

std::array<std::uint8_t, 3> pixel(const PreviewRaster& r, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * r.width + x) * 3;
  return {r.rgb[i], r.rgb[i + 1], r.rgb[i + 2]};
}

std::vector<float> ramp(int w, int h) {
  std::vector<float> v(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>(i);
  return v;
}

TEST(Colormap, EndpointsMatchTables) {
  // matplotlib inferno entries 0 and 255, rounded to 8 bits.
  EXPECT_EQ(colormap_rgb(Colormap::kInferno, 0.0), (std::array<std::uint8_t, 3>{0, 0, 4}));
  EXPECT_EQ(colormap_rgb(Colormap::kInferno, 1.0), (std::array<std::uint8_t, 3>{252, 255, 164}));
  EXPECT_EQ(colormap_rgb(Colormap::kInferno, 2.0), colormap_rgb(Colormap::kInferno, 1.0));
  EXPECT_EQ(colormap_rgb(Colormap::kGray, 0.0), (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_EQ(colormap_rgb(Colormap::kGray, 1.0), (std::array<std::uint8_t, 3>{255, 255, 255}));
  // Inferno is monotonic in lightness: red + green grows along the map.
  int previous = -1;
  for (int i = 0; i <= 100; ++i) {
    const auto c = colormap_rgb(Colormap::kInferno, i / 100.0);
    EXPECT_GE(c[0] + c[1], previous) << i;
    previous = c[0] + c[1];
  }
}

TEST(RenderPreview, UpscalesAndMapsPixels) {
  const int w = 4, h = 2;
  std::vector<float> v = {0, 1, 2, 3, 4, 5, 6, std::numeric_limits<float>::quiet_NaN()};
  PreviewOptions options;
  options.colormap = Colormap::kGray;
  options.title = "test";
  options.units = "K";
  const PreviewRaster r = render_preview(w, h, v, options);
  EXPECT_EQ(r.scale, 128);          // 2 rows -> at least 256 px tall
  EXPECT_GT(r.width, w * r.scale);  // room for the colour bar
  EXPECT_GT(r.image_y, 0);          // room for the title
  EXPECT_DOUBLE_EQ(r.min, 0.0);     // finite range: NaN ignored
  EXPECT_DOUBLE_EQ(r.max, 6.0);
  auto at = [&](int x, int y) {  // centre of data pixel (x, y)
    return pixel(r, r.image_x + x * r.scale + r.scale / 2, r.image_y + y * r.scale + r.scale / 2);
  };
  EXPECT_EQ(at(0, 0), (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_EQ(at(2, 1), (std::array<std::uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(at(3, 0), (std::array<std::uint8_t, 3>{128, 128, 128}));  // 3 of [0, 6]
  EXPECT_EQ(at(3, 1), (std::array<std::uint8_t, 3>{128, 128, 128}));  // NaN: mid grey
  // Nearest neighbour: every upscaled pixel of a data pixel has its colour.
  EXPECT_EQ(pixel(r, r.image_x, r.image_y), at(0, 0));
  EXPECT_EQ(pixel(r, r.image_x + r.scale - 1, r.image_y + r.scale - 1), at(0, 0));
}

TEST(RenderPreview, ExplicitRangeClamps) {
  PreviewOptions options;
  options.colormap = Colormap::kGray;
  options.min = 10.0;
  options.max = 20.0;
  const PreviewRaster r = render_preview(2, 1, {0.0f, 100.0f}, options);
  EXPECT_EQ(pixel(r, r.image_x + 1, r.image_y + 1), (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(r, r.image_x + r.scale + 1, r.image_y + 1),
            (std::array<std::uint8_t, 3>{255, 255, 255}));
  options.min = 30.0;  // min > max
  EXPECT_THROW(render_preview(2, 1, {0.0f, 1.0f}, options), InputError);
}

TEST_F(PngPreviewTest, WritesTextChunksAndColourBar) {
  const int w = 40, h = 30;
  PreviewOptions options;
  options.title = "ir / lwir band radiance";
  options.units = "W m⁻² sr⁻¹";
  const std::map<std::string, std::string> chunks = {
      {"obscura.provenance", R"({"software":"obscura","seed":1})"},
      {"Units", "W m⁻² sr⁻¹"}};  // non-ASCII: stored as iTXt
  const fs::path path = dir_ / "out" / "preview.png";
  write_png_preview(path, w, h, ramp(w, h), options, chunks);

  ASSERT_TRUE(fs::exists(path));
  const PngSize size = read_png_size(path);
  EXPECT_GE(size.height, 256);  // upscaled
  EXPECT_GT(size.width, w * (size.height / h) / 2);
  const PreviewRaster r = render_preview(w, h, ramp(w, h), options);
  EXPECT_EQ(size.width, r.width);
  EXPECT_EQ(size.height, r.height);
  EXPECT_GT(size.width, r.image_x + w * r.scale);  // colour bar to the right
  EXPECT_EQ(read_png_text_chunks(path), chunks);
}

TEST_F(PngPreviewTest, ConstantAndAllNanImagesWork) {
  const fs::path path = dir_ / "constant.png";
  write_png_preview(path, 3, 3, std::vector<float>(9, 2.5f), {}, {});
  EXPECT_GT(read_png_size(path).width, 3);
  const PreviewRaster r = render_preview(3, 3, std::vector<float>(9, 2.5f), {});
  EXPECT_LT(r.min, 2.5);
  EXPECT_GT(r.max, 2.5);
  EXPECT_TRUE(std::isfinite(r.max - r.min));
  const PreviewRaster zero = render_preview(1, 1, {0.0f}, {});
  EXPECT_LT(zero.min, zero.max);
  const PreviewRaster nan =
      render_preview(2, 1, std::vector<float>(2, std::numeric_limits<float>::quiet_NaN()), {});
  EXPECT_EQ(pixel(nan, nan.image_x, nan.image_y), (std::array<std::uint8_t, 3>{128, 128, 128}));
}

TEST_F(PngPreviewTest, BadInputsThrow) {
  const fs::path path = dir_ / "bad.png";
  EXPECT_THROW(write_png_preview(path, 2, 2, {1, 2, 3}, {}, {}), InputError);
  EXPECT_THROW(write_png_preview(path, 0, 1, {}, {}, {}), InputError);
  EXPECT_THROW(write_png_preview(path, 1, 1, {1}, {}, {{"", "x"}}), InputError);
  EXPECT_THROW(write_png_preview(path, 1, 1, {1}, {}, {{std::string(80, 'k'), "x"}}), InputError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_THROW(read_png_text_chunks(dir_ / "missing.png"), InputError);
  EXPECT_THROW(read_png_size(dir_ / "missing.png"), InputError);
  const fs::path junk = dir_ / "junk.png";
  {
    std::ofstream out(junk, std::ios::binary);
    out << "not a png at all";
  }
  EXPECT_THROW(read_png_text_chunks(junk), InputError);
  EXPECT_THROW(read_png_size(junk), InputError);
}

}  // namespace
}  // namespace obscura
