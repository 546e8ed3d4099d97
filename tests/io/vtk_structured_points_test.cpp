#include "obscura/io/vtk_structured_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "obscura/core/error.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class VtkStructuredPointsTest : public testing::TempDirTest {
 protected:
  fs::path write_file(const std::string& name, const std::string& bytes) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
  std::vector<std::string> dir_entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
};

using testing::contains;
using testing::expect_input_error;

// A 5x4x3 grid (every size distinct, so axis mix-ups show) with random
// values, a third of them zero, at an offset origin.
ScalarGrid make_grid(unsigned seed, float lo, float hi) {
  ScalarGrid g;
  g.dims = {5, 4, 3};
  g.placement.origin_m = {-3.25, 10.5, 0.125};
  g.placement.voxel_size_m = 0.75;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  g.values.resize(g.dims.count());
  for (float& v : g.values) v = (rng() % 3 == 0) ? 0.0f : u(rng);
  return g;
}

// Big-endian bytes of a value, as VTK legacy BINARY stores them.
template <typename T>
std::string be(T value) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t,
                               std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint16_t>>;
  const U u = std::bit_cast<U>(value);
  std::string s;
  for (int b = static_cast<int>(sizeof(T)) - 1; b >= 0; --b)
    s += static_cast<char>((u >> (8 * b)) & 0xff);
  return s;
}

std::string header(const std::string& encoding, const std::string& dims,
                   const std::string& spacing = "2 2 2") {
  return "# vtk DataFile Version 3.0\nhand-written test file\n" + encoding +
         "\nDATASET STRUCTURED_POINTS\nDIMENSIONS " + dims + "\nORIGIN 10 20 0\nSPACING " +
         spacing + "\n";
}

struct RoundTripCase {
  VtkEncoding encoding;
  VtkDataLocation location;
};

class VtkRoundTrip : public VtkStructuredPointsTest,
                     public ::testing::WithParamInterface<RoundTripCase> {};

TEST_P(VtkRoundTrip, ValuesExactAndGridPlaced) {
  const auto [encoding, location] = GetParam();
  ConcentrationFrame frame;
  frame.time_s = 4.5;
  frame.concentration_g_m3 = make_grid(1, 0.0f, 3.0f);
  frame.concentration_g_m3.values[7] = 1.0e-30f;  // tiny and huge values survive ASCII too
  frame.concentration_g_m3.values[8] = 3.4e38f;
  frame.temperature_k = make_grid(2, 250.0f, 900.0f);
  for (float& t : frame.temperature_k->values) t = t == 0.0f ? 288.15f : t;
  const fs::path path = dir_ / "frame.vtk";
  write_vtk_frame(path, frame, encoding, location);
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"frame.vtk"});  // no temporary left

  VtkArrayNames names;
  names.temperature = "temperature";
  const ConcentrationFrame back = read_vtk_structured_points(path, 4.5, names);
  EXPECT_EQ(back.time_s, 4.5);
  const ScalarGrid& c = back.concentration_g_m3;
  EXPECT_EQ(c.dims, frame.concentration_g_m3.dims);
  ASSERT_EQ(c.values.size(), frame.concentration_g_m3.values.size());
  EXPECT_EQ(std::memcmp(c.values.data(), frame.concentration_g_m3.values.data(),
                        c.values.size() * sizeof(float)),
            0);
  ASSERT_TRUE(back.temperature_k.has_value());
  EXPECT_EQ(back.temperature_k->values, frame.temperature_k->values);
  EXPECT_EQ(c.placement.voxel_size_m, 0.75);
  if (location == VtkDataLocation::kCells) {
    // Cells are the voxels: ORIGIN is origin_m itself, bit for bit.
    EXPECT_EQ(c.placement.origin_m, frame.concentration_g_m3.placement.origin_m);
  } else {
    // Points are voxel centres: ORIGIN = origin_m + h/2 and back, to rounding.
    EXPECT_NEAR(c.placement.origin_m.x, -3.25, 1e-12);
    EXPECT_NEAR(c.placement.origin_m.y, 10.5, 1e-12);
    EXPECT_NEAR(c.placement.origin_m.z, 0.125, 1e-12);
  }
  EXPECT_EQ(back.temperature_k->placement.origin_m, c.placement.origin_m);
}

INSTANTIATE_TEST_SUITE_P(
    Encodings, VtkRoundTrip,
    ::testing::Values(RoundTripCase{VtkEncoding::kAscii, VtkDataLocation::kPoints},
                      RoundTripCase{VtkEncoding::kBinary, VtkDataLocation::kPoints},
                      RoundTripCase{VtkEncoding::kAscii, VtkDataLocation::kCells},
                      RoundTripCase{VtkEncoding::kBinary, VtkDataLocation::kCells}),
    [](const auto& test) {
      return std::string(test.param.encoding == VtkEncoding::kAscii ? "Ascii" : "Binary") +
             (test.param.location == VtkDataLocation::kPoints ? "Points" : "Cells");
    });

TEST_F(VtkStructuredPointsTest, BinaryIsBigEndianFloat) {
  ScalarGrid g;
  g.dims = {1, 1, 1};
  g.values = {1.5f};
  const fs::path path = dir_ / "one.vtk";
  write_vtk_structured_points(path, {{"c", &g}}, VtkEncoding::kBinary);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(bytes, "LOOKUP_TABLE default\n" + be(1.5f) + "\n")) << bytes;
}

// A hand-written ASCII file in the shape CFD post-processors produce: mixed
// case keywords, an unrelated SCALARS array first, a VECTORS array, FIELD data
// at dataset level and in POINT_DATA, a METADATA block, and values spread
// unevenly over lines.
TEST_F(VtkStructuredPointsTest, HandWrittenAsciiPointDataMapsPointsToVoxelCentres) {
  const fs::path path = write_file(
      "hand.vtk", header("ASCII", "3 2 2") +
                      "FIELD FieldData 1\nTIME 1 1 double\n12.5\n"
                      "point_data 12\n"
                      "SCALARS rho double 1\nLOOKUP_TABLE default\n"
                      "1 1 1 1 1 1 1 1 1 1 1 1\n"
                      "METADATA\nINFORMATION 0\n\n"
                      "VECTORS wind float\n"
                      "1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0\n1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0\n"
                      "Scalars smoke%20mass float\nlookup_table default\n"
                      "0 1 2\n3 4 5 6 7\n8 9\n10\n11\n"
                      "FIELD FieldData 1\ntemp 1 12 int\n"
                      "300 301 302 303 304 305 306 307 308 309 310 311\n");
  VtkArrayNames names;
  names.concentration = "smoke mass";  // %20 decodes to a space, as in VTK
  names.temperature = "temp";
  const ConcentrationFrame f = read_vtk_structured_points(path, 1.0, names);
  const ScalarGrid& c = f.concentration_g_m3;
  ASSERT_EQ(c.dims, (GridDims{3, 2, 2}));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(c.at(i, j, k), i + 3 * j + 6 * k) << i << j << k;
  // Point (i,j,k) is at ORIGIN + 2·(i,j,k) and is the centre of voxel (i,j,k).
  EXPECT_EQ(c.placement.voxel_size_m, 2.0);
  EXPECT_EQ(c.placement.origin_m, Vec3(9, 19, -1));
  const Vec3 centre = c.placement.index_to_world({2, 1, 1});
  EXPECT_EQ(centre, Vec3(14, 22, 2));
  ASSERT_TRUE(f.temperature_k.has_value());
  EXPECT_EQ(f.temperature_k->at(2, 1, 1), 311.0f);
}

TEST_F(VtkStructuredPointsTest, HandWrittenCellDataCellsAreVoxels) {
  const fs::path path = write_file("cells.vtk", header("ASCII", "3 3 2") +
                                                    "CELL_DATA 4\nSCALARS concentration float 1\n"
                                                    "LOOKUP_TABLE default\n0.5 1.5 2.5 3.5\n");
  const ConcentrationFrame f = read_vtk_structured_points(path, 0.0);
  const ScalarGrid& c = f.concentration_g_m3;
  ASSERT_EQ(c.dims, (GridDims{2, 2, 1}));
  EXPECT_EQ(c.placement.origin_m, Vec3(10, 20, 0));  // cell (0,0,0) starts at ORIGIN
  EXPECT_EQ(c.at(1, 1, 0), 3.5f);
  EXPECT_FALSE(f.temperature_k.has_value());
}

// ParaView's legacy writer puts the active scalars in SCALARS and every other
// array in FIELD; here the concentration is a big-endian double FIELD array
// of a BINARY file, after a binary int array and a LOOKUP_TABLE to skip.
TEST_F(VtkStructuredPointsTest, BinaryFieldArrayOfDoubles) {
  std::string body =
      header("BINARY", "2 2 1") + "POINT_DATA 4\nSCALARS id int\nLOOKUP_TABLE mytable\n";
  for (int i : {7, 8, 9, 10}) body += be(static_cast<std::int32_t>(i));
  body += "\nLOOKUP_TABLE mytable 2\n" + std::string(8, '\x7f') + "\n";
  body += "FIELD FieldData 2\nother 2 4 short\n";
  for (int i = 0; i < 8; ++i) body += be(static_cast<std::int16_t>(-i));
  body += "\nconcentration 1 4 double\n";
  for (double v : {0.25, 0.5, 1e-3, 2e3}) body += be(v);
  body += "\n";
  const fs::path path = write_file("field.vtk", body);
  VtkArrayNames names;
  names.concentration_to_g_m3 = 1000.0;  // the file is in kg/m³
  const ConcentrationFrame f = read_vtk_structured_points(path, 3.0, names);
  const ScalarGrid& c = f.concentration_g_m3;
  ASSERT_EQ(c.dims, (GridDims{2, 2, 1}));
  EXPECT_EQ(c.values, (std::vector<float>{250.0f, 500.0f, 1.0f, 2e6f}));
}

// The layout VTK 9's vtkStructuredPointsWriter produces in BINARY: version
// 5.1, dataset-level FIELD data (a TIME value) before DIMENSIONS, SPACING
// before ORIGIN, and a METADATA block after each array.
TEST_F(VtkStructuredPointsTest, BinaryVtk51LayoutWithMetadata) {
  std::string body =
      "# vtk DataFile Version 5.1\nvtk output\nBINARY\nDATASET STRUCTURED_POINTS\n"
      "FIELD FieldData 1\nTIME 1 1 double\n" +
      be(12.0) +
      "\n"
      "METADATA\nINFORMATION 0\n\n"
      "DIMENSIONS 2 2 2\nSPACING 0.5 0.5 0.5\nORIGIN 1 2 3\nPOINT_DATA 8\n"
      "SCALARS concentration float 1\nLOOKUP_TABLE default\n";
  for (int i = 0; i < 8; ++i) body += be(0.125f * static_cast<float>(i));
  body +=
      "\nMETADATA\nINFORMATION 2\nNAME L2_NORM_RANGE LOCATION vtkDataArray\n"
      "DATA 2 0 0.875 \nNAME L2_NORM_FINITE_RANGE LOCATION vtkDataArray\n"
      "DATA 2 0 0.875 \n\n"
      "FIELD FieldData 1\nT 1 8 double\n";
  for (int i = 0; i < 8; ++i) body += be(300.0 + i);
  body += "\nMETADATA\nINFORMATION 0\n\n";
  const fs::path path = write_file("vtk51.vtk", body);
  VtkArrayNames names;
  names.temperature = "T";
  const ConcentrationFrame f = read_vtk_structured_points(path, 0.0, names);
  EXPECT_EQ(f.concentration_g_m3.at(1, 1, 1), 0.875f);
  EXPECT_EQ(f.concentration_g_m3.placement.origin_m, Vec3(0.75, 1.75, 2.75));
  ASSERT_TRUE(f.temperature_k.has_value());
  EXPECT_EQ(f.temperature_k->at(0, 1, 1), 306.0f);
}

TEST_F(VtkStructuredPointsTest, TruncatedBinaryNamesByteOffsetAndCount) {
  ConcentrationFrame frame;
  frame.concentration_g_m3 = make_grid(3, 0.0f, 1.0f);
  const fs::path path = dir_ / "full.vtk";
  write_vtk_frame(path, frame, VtkEncoding::kBinary);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t data_start = bytes.find("LOOKUP_TABLE default\n") + 21;
  // Cut 10 bytes out of the 60 floats (240 bytes) of data.
  const fs::path cut = write_file("cut.vtk", bytes.substr(0, data_start + 230));
  const InputError e = expect_input_error([&] { read_vtk_structured_points(cut, 0.0); });
  EXPECT_EQ(e.file(), cut.string());
  EXPECT_EQ(e.field(), "byte " + std::to_string(data_start));
  EXPECT_TRUE(contains(e.detail(), "truncated")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "60 float values need 240 bytes")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "10 bytes short")) << e.what();
}

TEST_F(VtkStructuredPointsTest, PointCountNotMatchingDimensions) {
  const fs::path path = write_file("dims.vtk", header("ASCII", "3 2 2") +
                                                   "POINT_DATA 10\nSCALARS concentration float\n"
                                                   "LOOKUP_TABLE default\n0 0 0 0 0 0 0 0 0 0\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "line 8");
  EXPECT_TRUE(contains(e.detail(), "POINT_DATA 10 does not match DIMENSIONS 3 2 2")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "12 points expected")) << e.what();
}

TEST_F(VtkStructuredPointsTest, FewerValuesThanDeclared) {
  const fs::path path = write_file(
      "short.vtk", header("ASCII", "3 2 2") +
                       "POINT_DATA 12\nSCALARS concentration float\nLOOKUP_TABLE default\n"
                       "0.000 1.000 2.000 3.000 4.000 5.000\n6.000 7.000 8.000 9.000\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "line 12");
  EXPECT_TRUE(contains(e.detail(), "file ends after 10 of 12 values")) << e.what();

  // Too few bytes left for the declared count even at two bytes a value: the
  // reader says so before allocating, at the array's line.
  const fs::path tiny = write_file("tiny.vtk", header("ASCII", "3 2 2") +
                                                   "POINT_DATA 12\nSCALARS concentration float\n"
                                                   "LOOKUP_TABLE default\n0 1 2 3 4 5\n");
  const InputError t = expect_input_error([&] { read_vtk_structured_points(tiny, 0.0); });
  EXPECT_EQ(t.field(), "line 9");
  EXPECT_TRUE(contains(t.detail(), "12 values cannot fit in the 13 bytes left")) << t.what();
}

TEST_F(VtkStructuredPointsTest, FewerValuesFollowedByAnotherArray) {
  const fs::path path = write_file(
      "short2.vtk", header("ASCII", "3 2 2") +
                        "POINT_DATA 12\nSCALARS concentration float\nLOOKUP_TABLE default\n"
                        "0 1 2 3 4 5 6 7 8 9\nSCALARS t float\nLOOKUP_TABLE default\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "line 12");
  EXPECT_TRUE(contains(e.detail(), "'SCALARS' is not a float value")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "fewer values than declared")) << e.what();
}

TEST_F(VtkStructuredPointsTest, MoreValuesThanDeclared) {
  const fs::path path = write_file(
      "long.vtk", header("ASCII", "3 2 2") +
                      "POINT_DATA 12\nSCALARS concentration float\nLOOKUP_TABLE default\n"
                      "0 1 2 3 4 5 6 7 8 9 10 11\n12\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "line 12");
  EXPECT_TRUE(contains(e.detail(),
                       "SCALARS 'concentration' (POINT_DATA, 12 x 1 float) has more "
                       "values than declared"))
      << e.what();
  // The same for dataset-level FIELD data, before any DIMENSIONS.
  const fs::path field =
      write_file("field.vtk",
                 "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"
                 "FIELD FieldData 1\nTIME 1 1 double\n12.5 13\nDIMENSIONS 2 1 1\n");
  const InputError f = expect_input_error([&] { read_vtk_structured_points(field, 0.0); });
  EXPECT_EQ(f.field(), "line 7");
  EXPECT_TRUE(contains(f.detail(), "FIELD 'TIME'")) << f.what();
}

TEST_F(VtkStructuredPointsTest, MissingArrayListsWhatExists) {
  const fs::path path =
      write_file("names.vtk", header("ASCII", "2 1 1") +
                                  "POINT_DATA 2\nSCALARS rho float\nLOOKUP_TABLE default\n1 2\n"
                                  "FIELD FieldData 1\nsoot_kg 1 2 double\n3 4\n");
  VtkArrayNames names;
  names.concentration = "soot";
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0, names); });
  EXPECT_EQ(e.field(), "soot");
  EXPECT_TRUE(contains(e.detail(), "no array named 'soot'")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "SCALARS 'rho'")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "FIELD 'soot_kg'")) << e.what();

  // The temperature is looked up the same way.
  names.concentration = "rho";
  names.temperature = "T";
  const InputError t = expect_input_error([&] { read_vtk_structured_points(path, 0.0, names); });
  EXPECT_EQ(t.field(), "T");
}

TEST_F(VtkStructuredPointsTest, NanNamesTheVoxel) {
  const fs::path ascii =
      write_file("nan.vtk", header("ASCII", "3 2 2") +
                                "POINT_DATA 12\nSCALARS concentration float\n"
                                "LOOKUP_TABLE default\n0 1 2 3 nan 5 6 7 8 9 10 11\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(ascii, 0.0); });
  EXPECT_EQ(e.field(), "concentration voxel (1,1,0)");  // index 4 = 1 + 3·1
  EXPECT_TRUE(contains(e.detail(), "not finite")) << e.what();

  std::string body = header("BINARY", "3 2 2") +
                     "POINT_DATA 12\nSCALARS concentration double\n"
                     "LOOKUP_TABLE default\n";
  for (int i = 0; i < 12; ++i) body += be(i == 11 ? std::numeric_limits<double>::quiet_NaN() : 1.0);
  const fs::path binary = write_file("nan_bin.vtk", body + "\n");
  const InputError b = expect_input_error([&] { read_vtk_structured_points(binary, 0.0); });
  EXPECT_EQ(b.field(), "concentration voxel (2,1,1)");
}

TEST_F(VtkStructuredPointsTest, NegativeConcentrationAndBadTemperature) {
  const fs::path path = write_file(
      "neg.vtk", header("ASCII", "2 1 1") +
                     "POINT_DATA 2\nSCALARS concentration float\nLOOKUP_TABLE default\n0 -1e-3\n"
                     "SCALARS T float\nLOOKUP_TABLE default\n300 0\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "concentration voxel (1,0,0)");
  EXPECT_TRUE(contains(e.detail(), "negative")) << e.what();

  const fs::path t = write_file(
      "badt.vtk", header("ASCII", "2 1 1") +
                      "POINT_DATA 2\nSCALARS concentration float\nLOOKUP_TABLE default\n0 1\n"
                      "SCALARS T float\nLOOKUP_TABLE default\n300 0\n");
  VtkArrayNames names;
  names.temperature = "T";
  const InputError te = expect_input_error([&] { read_vtk_structured_points(t, 0.0, names); });
  EXPECT_EQ(te.field(), "T voxel (1,0,0)");
}

TEST_F(VtkStructuredPointsTest, NonIsotropicSpacingRefused) {
  const fs::path path = write_file("aniso.vtk", header("ASCII", "2 2 2", "1 1 2") +
                                                    "POINT_DATA 8\nSCALARS concentration float\n"
                                                    "LOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(path, 0.0); });
  EXPECT_EQ(e.field(), "line 7");
  EXPECT_TRUE(contains(e.detail(), "cubic voxels")) << e.what();
  // Within the 1e-6 tolerance it is accepted, with the x spacing.
  const fs::path ok = write_file("near.vtk", header("ASCII", "2 2 2", "1 1.0000005 0.9999995") +
                                                 "POINT_DATA 8\nSCALARS concentration float\n"
                                                 "LOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n");
  EXPECT_EQ(read_vtk_structured_points(ok, 0.0).concentration_g_m3.placement.voxel_size_m, 1.0);
  // The spacing of a single-point axis places nothing and is ignored (2-D
  // slice writers put 0 or 1 there): the slice is one voxel thick.
  const fs::path slice = write_file("slice.vtk", header("ASCII", "2 1 1", "0.5 0 1") +
                                                     "POINT_DATA 2\nSCALARS concentration float\n"
                                                     "LOOKUP_TABLE default\n0 1\n");
  const ScalarGrid g = read_vtk_structured_points(slice, 0.0).concentration_g_m3;
  EXPECT_EQ(g.placement.voxel_size_m, 0.5);
  EXPECT_EQ(g.placement.origin_m, Vec3(9.75, 19.75, -0.25));
  const fs::path zero = write_file("zero.vtk", header("ASCII", "2 2 1", "0.5 0 1") +
                                                   "POINT_DATA 4\nSCALARS concentration float\n"
                                                   "LOOKUP_TABLE default\n0 1 2 3\n");
  const InputError z = expect_input_error([&] { read_vtk_structured_points(zero, 0.0); });
  EXPECT_EQ(z.field(), "line 7");
  EXPECT_TRUE(contains(z.detail(), "must be > 0")) << z.what();
}

TEST_F(VtkStructuredPointsTest, AspectRatioIsSpacing) {
  const fs::path path =
      write_file("aspect.vtk",
                 "# vtk DataFile Version 2.0\nold\nASCII\nDATASET STRUCTURED_POINTS\n"
                 "DIMENSIONS 2 1 1\nASPECT_RATIO 0.5 0.5 0.5\nORIGIN 0 0 0\nPOINT_DATA 2\n"
                 "SCALARS concentration float\nLOOKUP_TABLE default\n0 1\n");
  EXPECT_EQ(read_vtk_structured_points(path, 0.0).concentration_g_m3.placement.voxel_size_m, 0.5);
}

TEST_F(VtkStructuredPointsTest, HugeDimensionsRefusedBeforeAllocating) {
  const std::string dims = "100000 100000 100000";
  const fs::path ascii = write_file("huge.vtk", header("ASCII", dims) +
                                                    "POINT_DATA 1000000000000000\n"
                                                    "SCALARS concentration float\n"
                                                    "LOOKUP_TABLE default\n0 0 0\n");
  const InputError e = expect_input_error([&] { read_vtk_structured_points(ascii, 0.0); });
  EXPECT_EQ(e.field(), "line 9");
  EXPECT_TRUE(contains(e.detail(), "GiB of memory is available")) << e.what();

  const fs::path binary = write_file("huge_bin.vtk", header("BINARY", dims) +
                                                         "POINT_DATA 1000000000000000\n"
                                                         "SCALARS concentration float\n"
                                                         "LOOKUP_TABLE default\n" +
                                                         be(0.0f));
  const InputError b = expect_input_error([&] { read_vtk_structured_points(binary, 0.0); });
  EXPECT_TRUE(contains(b.detail(), "GiB of memory is available")) << b.what();

  // A size that fits in memory but not in the file is caught before
  // allocating too: binary by its byte count, ASCII by the bytes left.
  const fs::path cut = write_file("short_bin.vtk", header("BINARY", "1000 1000 100") +
                                                       "POINT_DATA 100000000\n"
                                                       "SCALARS concentration float\n"
                                                       "LOOKUP_TABLE default\n" +
                                                       be(0.0f));
  const InputError c = expect_input_error([&] { read_vtk_structured_points(cut, 0.0); });
  EXPECT_TRUE(contains(c.detail(), "400000000 bytes")) << c.what();
}

TEST_F(VtkStructuredPointsTest, MalformedHeaders) {
  const auto field_of = [&](const std::string& name, const std::string& text) {
    const fs::path p = write_file(name, text);
    return expect_input_error([&] { read_vtk_structured_points(p, 0.0); });
  };
  const InputError not_vtk = field_of("a.vtk", "hello\n");
  EXPECT_EQ(not_vtk.field(), "line 1");
  const InputError rect = field_of(
      "b.vtk",
      "# vtk DataFile Version 3.0\nt\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\n");
  EXPECT_EQ(rect.field(), "line 4");
  EXPECT_TRUE(contains(rect.detail(), "only STRUCTURED_POINTS")) << rect.what();
  const InputError enc = field_of("c.vtk", "# vtk DataFile Version 3.0\nt\nXML\n");
  EXPECT_EQ(enc.field(), "line 3");
  const InputError bad_value =
      field_of("d.vtk", header("ASCII", "2 1 1") +
                            "POINT_DATA 2\nSCALARS concentration float\nLOOKUP_TABLE default\n"
                            "0\n1.2.3\n");
  EXPECT_EQ(bad_value.field(), "line 12");
  EXPECT_TRUE(contains(bad_value.detail(), "'1.2.3' is not a float value")) << bad_value.what();
  const InputError no_spacing =
      field_of("e.vtk",
               "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"
               "DIMENSIONS 2 1 1\nORIGIN 0 0 0\nPOINT_DATA 2\n");
  EXPECT_EQ(no_spacing.field(), "line 7");
  EXPECT_TRUE(contains(no_spacing.detail(), "SPACING")) << no_spacing.what();
  const InputError two_components =
      field_of("f.vtk", header("ASCII", "2 1 1") +
                            "POINT_DATA 2\nSCALARS concentration float 2\n"
                            "LOOKUP_TABLE default\n0 0 1 1\n");
  EXPECT_TRUE(contains(two_components.detail(), "2 components")) << two_components.what();
  const InputError flat_cells = field_of("g.vtk", header("ASCII", "3 3 1") +
                                                      "CELL_DATA 4\nSCALARS concentration float\n"
                                                      "LOOKUP_TABLE default\n0 0 1 1\n");
  EXPECT_TRUE(contains(flat_cells.detail(), "flat cells")) << flat_cells.what();
}

TEST_F(VtkStructuredPointsTest, NonExistentFile) {
  const fs::path missing = dir_ / "nope.vtk";
  const InputError e = expect_input_error([&] { read_vtk_structured_points(missing, 0.0); });
  EXPECT_EQ(e.file(), missing.string());
  EXPECT_EQ(e.detail(), "file not found");
}

TEST_F(VtkStructuredPointsTest, SeriesSharesGridAndKeepsTimes) {
  std::vector<std::pair<double, std::string>> files;
  std::vector<ConcentrationFrame> written;
  for (int f = 0; f < 3; ++f) {
    ConcentrationFrame frame;
    frame.concentration_g_m3 = make_grid(10 + f, 0.0f, 2.0f);
    const fs::path p = dir_ / ("t" + std::to_string(f) + ".vtk");
    write_vtk_frame(p, frame, f % 2 ? VtkEncoding::kAscii : VtkEncoding::kBinary);
    files.emplace_back(0.5 + 1.25 * f, p.string());
    written.push_back(std::move(frame));
  }
  const ConcentrationSeries s = read_vtk_series(files);
  ASSERT_EQ(s.frames.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(s.frames[f].time_s, 0.5 + 1.25 * f);
    EXPECT_EQ(s.frames[f].concentration_g_m3.values, written[f].concentration_g_m3.values);
    EXPECT_EQ(s.frames[f].concentration_g_m3.placement.origin_m,
              s.frames[0].concentration_g_m3.placement.origin_m);
  }
  EXPECT_TRUE(contains(s.source, "t0.vtk")) << s.source;
}

TEST_F(VtkStructuredPointsTest, SeriesRefusesUnsortedTimesBeforeReading) {
  // The files do not exist: the time order is checked first.
  const std::vector<std::pair<double, std::string>> files = {{0.0, (dir_ / "a.vtk").string()},
                                                             {2.0, (dir_ / "b.vtk").string()},
                                                             {1.0, (dir_ / "c.vtk").string()}};
  const InputError e = expect_input_error([&] { read_vtk_series(files); });
  EXPECT_EQ(e.file(), (dir_ / "c.vtk").string());
  EXPECT_EQ(e.field(), "time[2]");
  EXPECT_TRUE(contains(e.detail(), "strictly increasing")) << e.what();
  const InputError dup = expect_input_error([&] {
    read_vtk_series({{1.0, files[0].second}, {1.0, files[1].second}});
  });
  EXPECT_EQ(dup.field(), "time[1]");
}

TEST_F(VtkStructuredPointsTest, SeriesRefusesDifferentGrids) {
  ConcentrationFrame a, b;
  a.concentration_g_m3 = make_grid(1, 0.0f, 1.0f);
  b.concentration_g_m3 = make_grid(2, 0.0f, 1.0f);
  b.concentration_g_m3.placement.origin_m.x += 0.75;  // one voxel over
  write_vtk_frame(dir_ / "a.vtk", a, VtkEncoding::kBinary);
  write_vtk_frame(dir_ / "b.vtk", b, VtkEncoding::kBinary);
  const InputError e = expect_input_error([&] {
    read_vtk_series({{0.0, (dir_ / "a.vtk").string()}, {1.0, (dir_ / "b.vtk").string()}});
  });
  EXPECT_EQ(e.file(), (dir_ / "b.vtk").string());
  EXPECT_EQ(e.field(), "grid");
  EXPECT_TRUE(contains(e.detail(), "must share one grid")) << e.what();
}

TEST_F(VtkStructuredPointsTest, WriterRefusesMismatchedArraysAndLeavesNothing) {
  const ScalarGrid a = make_grid(1, 0.0f, 1.0f);
  ScalarGrid b = make_grid(2, 0.0f, 1.0f);
  b.placement.voxel_size_m = 0.5;
  const fs::path path = dir_ / "out.vtk";
  EXPECT_THROW(write_vtk_structured_points(path, {{"a", &a}, {"b", &b}}, VtkEncoding::kAscii),
               InputError);
  EXPECT_THROW(write_vtk_structured_points(path, {{"a", &a}, {"a", &a}}, VtkEncoding::kAscii),
               InputError);
  ScalarGrid short_values = a;
  short_values.values.pop_back();
  EXPECT_THROW(write_vtk_structured_points(path, {{"a", &short_values}}, VtkEncoding::kBinary),
               InputError);
  EXPECT_TRUE(dir_entries().empty());
}

}  // namespace
}  // namespace obscura
