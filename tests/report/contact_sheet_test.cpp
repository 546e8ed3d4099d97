// The contact sheet (io/contact_sheet.h): layout and size caps, one colour
// scale per row, resampling, thumbnails and the choice of frames.
#include "obscura/report/contact_sheet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "obscura/core/error.h"
#include "obscura/io/png_file.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

ContactSheetCell gradient(int w, int h, float offset) {
  ContactSheetCell c;
  c.width = w;
  c.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) c.values.push_back(offset + static_cast<float>(x + y));
  return c;
}

ContactSheet two_by_three() {
  ContactSheet sheet;
  sheet.title = "test sheet";
  sheet.times_s = {0, 1.5, 3};
  for (int r = 0; r < 2; ++r) {
    ContactSheetRow row;
    row.label = r == 0 ? "ir / lwir" : "tv / visible";
    row.quantity = r == 0 ? "apparent temperature" : "band radiance";
    row.units = r == 0 ? "K" : "W m⁻² sr⁻¹";
    for (int c = 0; c < 3; ++c) row.cells.push_back(gradient(r == 0 ? 20 : 30, 10, 100.0f * c));
    sheet.rows.push_back(row);
  }
  return sheet;
}

std::array<std::uint8_t, 3> pixel(const ContactSheetRaster& r, int x, int y) {
  const std::uint8_t* p = &r.rgb[(static_cast<std::size_t>(y) * r.width + x) * 3];
  return {p[0], p[1], p[2]};
}

TEST(ContactSheet, LayoutHoldsEveryCellWithContent) {
  const ContactSheetRaster r = render_contact_sheet(two_by_three());
  EXPECT_EQ(r.rgb.size(), static_cast<std::size_t>(r.width) * r.height * 3);
  EXPECT_EQ(r.cell_height, 160);
  EXPECT_EQ(r.cell_widths, (std::vector<int>{320, 480}));
  ASSERT_EQ(r.cell_x.size(), 3u);
  ASSERT_EQ(r.cell_y.size(), 2u);
  EXPECT_GE(r.width, r.cell_x.back() + 480);
  EXPECT_GE(r.height, r.cell_y.back() + 160);
  // One scale per row over all its frames.
  EXPECT_DOUBLE_EQ(r.row_min[0], 0.0);
  EXPECT_DOUBLE_EQ(r.row_max[0], 200.0 + 19 + 9);
  // Cells are not constant, and the same pixel differs between frames.
  std::set<std::array<std::uint8_t, 3>> colours;
  for (int x = 0; x < 320; x += 16)
    colours.insert(pixel(r, r.cell_x[0] + 80 + x / 4, r.cell_y[0] + 80));
  EXPECT_GT(colours.size(), 3u);
  EXPECT_NE(pixel(r, r.cell_x[0] + 80 + 10, r.cell_y[0] + 5),
            pixel(r, r.cell_x[2] + 80 + 10, r.cell_y[0] + 5));
}

TEST(ContactSheet, SharedRowScaleMapsFramesToTheEndsOfTheColourmap) {
  ContactSheet sheet;
  sheet.times_s = {0, 1};
  ContactSheetRow row;
  row.label = "s / b";
  row.quantity = "q";
  ContactSheetCell lo{4, 4, std::vector<float>(16, 1.0f)}, hi{4, 4, std::vector<float>(16, 2.0f)};
  row.cells = {lo, hi};
  sheet.rows.push_back(row);
  const ContactSheetRaster r = render_contact_sheet(sheet);
  EXPECT_EQ(pixel(r, r.cell_x[0] + 80, r.cell_y[0] + 80), colormap_rgb(Colormap::kInferno, 0.0));
  EXPECT_EQ(pixel(r, r.cell_x[1] + 80, r.cell_y[0] + 80), colormap_rgb(Colormap::kInferno, 1.0));
}

TEST(ContactSheet, ShrinksCellsToFitTheSizeCap) {
  ContactSheet sheet = two_by_three();
  sheet.max_size_px = 800;
  const ContactSheetRaster r = render_contact_sheet(sheet);
  EXPECT_LE(r.width, 800);
  EXPECT_LE(r.height, 800);
  EXPECT_LT(r.cell_height, 160);
  EXPECT_GE(r.cell_height, 8);
  sheet.max_size_px = 64;  // cannot hold 3 columns of labelled cells
  EXPECT_THROW(render_contact_sheet(sheet), Error);
}

TEST(ContactSheet, RejectsInconsistentRows) {
  ContactSheet sheet = two_by_three();
  sheet.rows[0].cells.pop_back();
  EXPECT_THROW(render_contact_sheet(sheet), Error);
  sheet = two_by_three();
  sheet.rows[1].cells[1] = gradient(5, 5, 0);
  EXPECT_THROW(render_contact_sheet(sheet), Error);
  sheet = two_by_three();
  sheet.rows[1].cells[1].values.pop_back();
  EXPECT_THROW(render_contact_sheet(sheet), Error);
  sheet = two_by_three();
  sheet.rows[0].min = 5.0;
  sheet.rows[0].max = 1.0;
  EXPECT_THROW(render_contact_sheet(sheet), Error);
  sheet = two_by_three();
  sheet.rows[0].cells[1] = ContactSheetCell{};  // a blank cell is allowed
  EXPECT_NO_THROW(render_contact_sheet(sheet));
  EXPECT_THROW(render_contact_sheet(ContactSheet{}), Error);
}

class ContactSheetFile : public testing::TempDirTest {};

TEST_F(ContactSheetFile, WritesAPngOfTheRasterSizeWithProvenance) {
  const ContactSheet sheet = two_by_three();
  const ContactSheetRaster r = render_contact_sheet(sheet);
  const auto path = dir_ / "sheet.png";
  write_contact_sheet_png(path, sheet, R"({"software":"obscura"})");
  const PngSize size = read_png_size(path);
  EXPECT_EQ(size.width, r.width);
  EXPECT_EQ(size.height, r.height);
  EXPECT_EQ(read_png_text_chunks(path).at("obscura.provenance"), R"({"software":"obscura"})");
}

TEST(ResampleImage, AveragesWhenShrinkingAndRepeatsWhenEnlarging) {
  // 4 × 2 → 2 × 1: means of 2 × 2 blocks; a NaN is left out of its mean.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> v = {1, 3, 5, nan, 3, 1, 7, 9};
  const auto small = resample_image(4, 2, v, 2, 1);
  EXPECT_FLOAT_EQ(small[0], 2.0f);
  EXPECT_FLOAT_EQ(small[1], 7.0f);
  // 3 → 2 across: overlaps of 1.5 source pixels, weights 1 and 0.5.
  const auto third = resample_image(3, 1, {0, 3, 6}, 2, 1);
  EXPECT_FLOAT_EQ(third[0], 1.0f);
  EXPECT_FLOAT_EQ(third[1], 5.0f);
  const auto big = resample_image(2, 1, {1, 2}, 4, 2);
  EXPECT_EQ(big, (std::vector<float>{1, 1, 2, 2, 1, 1, 2, 2}));
  EXPECT_TRUE(std::isnan(resample_image(1, 1, {nan}, 1, 1)[0]));
  EXPECT_THROW(resample_image(2, 2, {1, 2, 3}, 1, 1), Error);
}

TEST(ContactSheetThumbnail, ShrinksLargeImagesOnly) {
  const auto big = contact_sheet_thumbnail(1000, 500, std::vector<float>(500000, 2.0f), 256);
  EXPECT_EQ(big.width, 256);
  EXPECT_EQ(big.height, 128);
  EXPECT_FLOAT_EQ(big.values[1000], 2.0f);
  const auto small = contact_sheet_thumbnail(20, 10, std::vector<float>(200, 1.0f), 256);
  EXPECT_EQ(small.width, 20);
  EXPECT_EQ(small.height, 10);
}

TEST(ContactSheetFrames, SpreadsEvenlyKeepingTheEnds) {
  EXPECT_EQ(contact_sheet_frames(4, 10), (std::vector<std::size_t>{0, 1, 2, 3}));
  const auto f = contact_sheet_frames(25, 10);
  ASSERT_EQ(f.size(), 10u);
  EXPECT_EQ(f.front(), 0u);
  EXPECT_EQ(f.back(), 24u);
  for (std::size_t i = 1; i < f.size(); ++i) EXPECT_GT(f[i], f[i - 1]);
  EXPECT_EQ(contact_sheet_frames(5, 1), (std::vector<std::size_t>{0}));
  EXPECT_TRUE(contact_sheet_frames(0, 10).empty());
}

}  // namespace
}  // namespace obscura
