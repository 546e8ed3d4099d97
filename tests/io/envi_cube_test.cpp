// ENVI cubes (io/envi_cube.h): the header the ENVI format defines and the
// band-sequential float layout. GDAL reading them is tested from Python
// (python/tests/test_envi_output.py).
#include "obscura/io/envi_cube.h"

#include <gtest/gtest.h>

#include <cstring>

#include "obscura/core/error.h"
#include "support/file_bytes.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class EnviCubeTest : public testing::TempDirTest {};

TEST_F(EnviCubeTest, BandsFollowOneAnotherAsLittleEndianFloats) {
  const std::vector<float> a = {1, 2, 3, 4, 5, 6}, b = {-1, -2, -3, -4, -5, -6.5f};
  EnviCube cube{
      3, 2, {{"visible", 0.55, 0.3, a.data()}, {"8:12", 10, 4, b.data()}}, "W m-2 sr-1", "a test"};
  write_envi_cube(dir_ / "c.img", cube);
  const testing::Bytes bytes = testing::read_file_bytes(dir_ / "c.img");
  ASSERT_EQ(bytes.size(), 12 * sizeof(float));
  std::vector<float> back(12);
  std::memcpy(back.data(), bytes.data(), bytes.size());
  EXPECT_EQ(back, (std::vector<float>{1, 2, 3, 4, 5, 6, -1, -2, -3, -4, -5, -6.5f}));
  const testing::Bytes hdr = testing::read_file_bytes(dir_ / "c.hdr");
  EXPECT_EQ(std::string(hdr.begin(), hdr.end()), envi_header_text(cube));
}

TEST_F(EnviCubeTest, TheHeaderNamesSizeLayoutBandsAndUnits) {
  const std::vector<float> v(6, 0.0f);
  const std::string h =
      envi_header_text({3,
                        2,
                        {{"visible", 0.55, 0.3, v.data()}, {"odd{name},x", 10, 4, v.data()}},
                        "W m-2 sr-1",
                        "sensor ir, t = 2 s"});
  EXPECT_EQ(h.rfind("ENVI\n", 0), 0u) << h;
  for (const char* line :
       {"samples = 3\n", "lines = 2\n", "bands = 2\n", "header offset = 0\n", "data type = 4\n",
        "interleave = bsq\n", "byte order = 0\n", "band names = {visible, odd_name__x}\n",
        "wavelength units = Micrometers\n", "wavelength = {0.55, 10}\n", "fwhm = {0.3, 4}\n",
        "data units = W m-2 sr-1\n", "description = {sensor ir, t = 2 s}\n"})
    EXPECT_NE(h.find(line), std::string::npos) << line << "\nin\n" << h;
}

TEST_F(EnviCubeTest, ACubeWithoutBandsOrPixelsIsRefusedAndNothingIsWritten) {
  const std::vector<float> v(1, 0.0f);
  EXPECT_THROW(write_envi_cube(dir_ / "e.img", {1, 1, {}, "", ""}), InputError);
  EXPECT_THROW(write_envi_cube(dir_ / "e.img", {0, 1, {{"b", 1, 1, v.data()}}, "", ""}),
               InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

}  // namespace
}  // namespace obscura
