#include "obscura/io/exr_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "obscura/core/error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class ExrWriterTest : public testing::TempDirTest {};

// Bitwise equality, so NaN payloads, -0 and denormals are checked too.
bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST_F(ExrWriterTest, RoundTripIsExact) {
  const int w = 7, h = 5;  // odd sizes catch stride and row-order mistakes
  ExrChannel radiance{"lwir.radiance", {}};
  ExrChannel depth{"depth", {}};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      radiance.pixels.push_back(1e-3f * static_cast<float>(y * w + x) + 1.0f / 3.0f);
      depth.pixels.push_back(static_cast<float>(100 * y + x));  // top row first
    }
  }
  radiance.pixels[3] = std::numeric_limits<float>::quiet_NaN();
  radiance.pixels[4] = std::numeric_limits<float>::infinity();
  radiance.pixels[5] = -0.0f;
  radiance.pixels[6] = std::numeric_limits<float>::denorm_min();
  const std::map<std::string, std::string> attributes = {
      {"obscura.provenance", R"({"software":"obscura","seed":7})"},
      {"obscura.units.lwir.radiance", "W m⁻² sr⁻¹"},
      {"obscura.units.depth", "m"}};

  // Numbers are stored as numbers: read back bit for bit, not as text.
  const std::map<std::string, double> numbers = {{"obscura.time_s", 0.1 + 0.2},
                                                 {"obscura.band.lwir.min_um", 8.0}};
  const std::map<std::string, int> counts = {{"obscura.band.lwir.response_points", 2}};

  const fs::path path = dir_ / "nested" / "image.exr";
  write_exr(path, w, h, {radiance, depth}, attributes, numbers, counts);
  const ExrImage image = read_exr(path);

  EXPECT_EQ(image.width, w);
  EXPECT_EQ(image.height, h);
  ASSERT_EQ(image.channels.size(), 2u);
  ASSERT_TRUE(image.channels.count("lwir.radiance"));
  ASSERT_TRUE(image.channels.count("depth"));
  const auto& r = image.channels.at("lwir.radiance");
  const auto& d = image.channels.at("depth");
  ASSERT_EQ(r.size(), radiance.pixels.size());
  for (size_t i = 0; i < r.size(); ++i) {
    EXPECT_TRUE(same_bits(r[i], radiance.pixels[i])) << "pixel " << i;
    EXPECT_EQ(d[i], depth.pixels[i]) << "pixel " << i;
  }
  for (const auto& [name, value] : attributes) {
    ASSERT_TRUE(image.string_attributes.count(name)) << name;
    EXPECT_EQ(image.string_attributes.at(name), value);
  }
  for (const auto& [name, value] : numbers) {
    ASSERT_TRUE(image.double_attributes.count(name)) << name;
    EXPECT_EQ(image.double_attributes.at(name), value) << name;  // exact: 0.30000000000000004
    EXPECT_FALSE(image.string_attributes.count(name)) << name;
  }
  EXPECT_EQ(image.int_attributes.at("obscura.band.lwir.response_points"), 2);
  // No temporary file is left next to the output.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(path.parent_path())) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(ExrWriterTest, OverwritesExistingFile) {
  const fs::path path = dir_ / "a.exr";
  write_exr(path, 1, 1, {{"Y", {1.0f}}}, {});
  write_exr(path, 2, 1, {{"Y", {2.0f, 3.0f}}}, {});
  const ExrImage image = read_exr(path);
  EXPECT_EQ(image.width, 2);
  EXPECT_EQ(image.channels.at("Y"), (std::vector<float>{2.0f, 3.0f}));
}

TEST_F(ExrWriterTest, RejectsBadArguments) {
  const fs::path path = dir_ / "bad.exr";
  EXPECT_THROW(write_exr(path, 2, 2, {{"Y", {1, 2, 3}}}, {}), InputError);        // pixel count
  EXPECT_THROW(write_exr(path, 0, 2, {{"Y", {}}}, {}), InputError);               // size
  EXPECT_THROW(write_exr(path, 1, 1, {{"", {1}}}, {}), InputError);               // empty name
  EXPECT_THROW(write_exr(path, 1, 1, {{"Y", {1}}, {"Y", {2}}}, {}), InputError);  // duplicate
  EXPECT_THROW(write_exr(path, 1, 1, {}, {}), InputError);                        // no channel
  EXPECT_THROW(write_exr(path, 1, 1, {{"Y", {1}}}, {{"channels", "x"}}), InputError);  // reserved
  EXPECT_THROW(write_exr(path, 1, 1, {{"Y", {1}}}, {}, {{"lineOrder", 1.0}}), InputError);
  EXPECT_THROW(write_exr(path, 1, 1, {{"Y", {1}}}, {{"a", "x"}}, {{"a", 1.0}}),
               InputError);  // twice
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(ExrWriterTest, ReadingGarbageOrMissingFileThrowsInputError) {
  EXPECT_THROW(read_exr(dir_ / "missing.exr"), InputError);
  const fs::path junk = dir_ / "junk.exr";
  {
    std::ofstream out(junk, std::ios::binary);
    out << "this is not an EXR file";
  }
  EXPECT_THROW(read_exr(junk), InputError);
}

}  // namespace
}  // namespace obscura
