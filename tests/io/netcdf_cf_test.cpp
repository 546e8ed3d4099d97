#include "obscura/io/netcdf_cf.h"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

// A variable of a hand-made test file: written with the netCDF C API directly,
// so the tests do not depend on obscura's writer to make the files they read.
struct TestVar {
  std::string name;
  nc_type type = NC_DOUBLE;
  std::vector<std::string> dims;
  std::vector<double> data;  // C order over dims; empty: not written
  std::map<std::string, std::string> text;
  std::map<std::string, double> numbers;  // stored in the variable's type
};

void nc_ok(int status) { ASSERT_EQ(status, NC_NOERR) << nc_strerror(status); }

void make_netcdf(const fs::path& path, const std::vector<std::pair<std::string, std::size_t>>& dims,
                 const std::vector<TestVar>& vars) {
  int nc = -1;
  nc_ok(nc_create(path.c_str(), NC_NETCDF4 | NC_CLOBBER, &nc));
  std::map<std::string, int> dim_ids;
  for (const auto& [name, len] : dims) nc_ok(nc_def_dim(nc, name.c_str(), len, &dim_ids[name]));
  std::vector<int> var_ids;
  for (const TestVar& v : vars) {
    std::vector<int> ids;
    for (const std::string& d : v.dims) ids.push_back(dim_ids.at(d));
    int id = -1;
    nc_ok(nc_def_var(nc, v.name.c_str(), v.type, static_cast<int>(ids.size()), ids.data(), &id));
    for (const auto& [att, value] : v.text)
      nc_ok(nc_put_att_text(nc, id, att.c_str(), value.size(), value.c_str()));
    // CF §8.1: scale_factor and add_offset have the unpacked type; _FillValue
    // and missing_value the variable's own.
    for (const auto& [att, value] : v.numbers)
      nc_ok(nc_put_att_double(nc, id, att.c_str(),
                              att == "scale_factor" || att == "add_offset" ? NC_DOUBLE : v.type, 1,
                              &value));
    var_ids.push_back(id);
  }
  nc_ok(nc_enddef(nc));
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const TestVar& v = vars[i];
    if (v.data.empty()) continue;
    // The unlimited dimension gets whatever length the data implies.
    std::vector<std::size_t> start(v.dims.size(), 0), count;
    std::size_t fixed = 1;
    for (const std::string& d : v.dims) {
      const auto it =
          std::find_if(dims.begin(), dims.end(), [&](const auto& p) { return p.first == d; });
      count.push_back(it->second);
      if (it->second != NC_UNLIMITED) fixed *= it->second;
    }
    for (std::size_t& c : count)
      if (c == NC_UNLIMITED) c = v.data.size() / fixed;
    nc_ok(nc_put_vara_double(nc, var_ids[i], start.data(), count.data(), v.data.data()));
  }
  nc_ok(nc_close(nc));
}

std::vector<double> linspace(double first, double step, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = first + step * static_cast<double>(i);
  return v;
}

TestVar coordinate(const std::string& name, std::vector<double> values, const std::string& units) {
  return TestVar{name, NC_DOUBLE, {name}, std::move(values), {{"units", units}}, {}};
}

using testing::contains;
using testing::expect_input_error;

class NetcdfCfTest : public testing::TempDirTest {
 protected:
  std::vector<std::string> dir_entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  // A CF (time, z, y, x) file of 2 steps on 4 x 3 x 2 voxels of 0.5 m with
  // the voxel centre of (0,0,0) at (1, 2, 3) m; concentration value
  // i + 10 j + 100 k + 1000 t; an unused dimension "nv". `edit` changes the
  // variables before writing.
  fs::path small_file(const std::string& name,
                      const std::function<void(std::vector<TestVar>&)>& edit = {}) {
    std::vector<double> c;
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 4; ++i) c.push_back(i + 10 * j + 100 * k + 1000 * t);
    std::vector<TestVar> vars = {
        coordinate("time", {0.0, 30.0}, "seconds since 2024-01-01 00:00:00"),
        coordinate("z", linspace(3.0, 0.5, 2), "m"), coordinate("y", linspace(2.0, 0.5, 3), "m"),
        coordinate("x", linspace(1.0, 0.5, 4), "m"),
        TestVar{"concentration", NC_FLOAT, {"time", "z", "y", "x"}, c, {{"units", "g m-3"}}, {}}};
    if (edit) edit(vars);
    const fs::path p = dir_ / name;
    make_netcdf(p, {{"time", NC_UNLIMITED}, {"z", 2}, {"y", 3}, {"x", 4}, {"nv", 2}}, vars);
    return p;
  }

  static TestVar& var(std::vector<TestVar>& vars, const std::string& name) {
    return *std::find_if(vars.begin(), vars.end(),
                         [&](const TestVar& v) { return v.name == name; });
  }
};

ScalarGrid random_grid(unsigned seed, float lo, float hi) {
  ScalarGrid g;
  g.dims = {5, 4, 3};
  g.placement.origin_m = {-3.25, 10.5, 0.125};
  g.placement.voxel_size_m = 0.75;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  g.values.resize(g.dims.count());
  for (float& v : g.values) v = (rng() % 3 == 0) ? lo : u(rng);
  return g;
}

TEST_F(NetcdfCfTest, RoundTripExactValuesTimesAndPlacement) {
  ConcentrationSeries s;
  s.source = "unit test";
  for (int f = 0; f < 3; ++f) {
    ConcentrationFrame frame;
    frame.time_s = 0.1 + 2.5 * f;  // not exact in binary: must still come back bit for bit
    frame.concentration_g_m3 = random_grid(f, 0.0f, 4.0f);
    frame.concentration_g_m3.values[3] = 3.0e-38f;
    frame.temperature_k = random_grid(100 + f, 250.0f, 1200.0f);
    s.frames.push_back(std::move(frame));
  }
  const fs::path path = dir_ / "series.nc";
  write_netcdf_cf(path, s);
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"series.nc"});  // no temporary left

  NetcdfReadOptions options;
  options.temperature = "temperature";
  const ConcentrationSeries back = read_netcdf_cf(path, options);
  EXPECT_EQ(back.source, path.string());
  ASSERT_EQ(back.frames.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    const ConcentrationFrame& a = s.frames[f];
    const ConcentrationFrame& b = back.frames[f];
    EXPECT_EQ(b.time_s, a.time_s);
    EXPECT_EQ(b.concentration_g_m3.dims, a.concentration_g_m3.dims);
    ASSERT_EQ(b.concentration_g_m3.values.size(), a.concentration_g_m3.values.size());
    EXPECT_EQ(std::memcmp(b.concentration_g_m3.values.data(), a.concentration_g_m3.values.data(),
                          a.concentration_g_m3.values.size() * sizeof(float)),
              0);
    ASSERT_TRUE(b.temperature_k.has_value());
    EXPECT_EQ(b.temperature_k->values, a.temperature_k->values);
    // Coordinates are voxel centres written in double: placement to rounding.
    const GridPlacement& p = b.concentration_g_m3.placement;
    EXPECT_NEAR(p.voxel_size_m, 0.75, 1e-14);
    EXPECT_NEAR(p.origin_m.x, -3.25, 1e-12);
    EXPECT_NEAR(p.origin_m.y, 10.5, 1e-12);
    EXPECT_NEAR(p.origin_m.z, 0.125, 1e-12);
    EXPECT_EQ(b.temperature_k->placement.origin_m, p.origin_m);
  }
}

TEST_F(NetcdfCfTest, HandWrittenCfOrder) {
  const fs::path path = small_file("small.nc");
  const ConcentrationSeries s = read_netcdf_cf(path);
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].time_s, 0.0);
  EXPECT_EQ(s.frames[1].time_s, 30.0);  // "seconds since …": offsets in s
  const ScalarGrid& g = s.frames[1].concentration_g_m3;
  ASSERT_EQ(g.dims, (GridDims{4, 3, 2}));
  EXPECT_EQ(g.at(3, 2, 1), 3 + 20 + 100 + 1000);
  EXPECT_EQ(g.placement.voxel_size_m, 0.5);
  // x[0] = 1 m is the centre of voxel (0,0,0): the corner is half a voxel lower.
  EXPECT_EQ(g.placement.origin_m, Vec3(0.75, 1.75, 2.75));
  EXPECT_FALSE(s.frames[0].temperature_k.has_value());
}

// Dimensions in a non-CF order, identified by name or by the axis attribute,
// with a decreasing axis, km, minutes and kg m-3 — all converted.
TEST_F(NetcdfCfTest, PermutedDimensionsUnitsAndDecreasingAxis) {
  const std::size_t nx = 4, ny = 3, nz = 2, nt = 2;
  // Variable dims (northing, t, x, z): y is called "northing" (axis = "Y")
  // and stored north to south.
  std::vector<double> c;
  for (std::size_t jf = 0; jf < ny; ++jf)
    for (std::size_t t = 0; t < nt; ++t)
      for (std::size_t i = 0; i < nx; ++i)
        for (std::size_t k = 0; k < nz; ++k) {
          const std::size_t j = ny - 1 - jf;  // file row jf is grid row j
          c.push_back(1e-3 * static_cast<double>(i + 10 * j + 100 * k + 1000 * t));
        }
  TestVar northing = coordinate("northing", {2.004, 2.002, 2.000}, "km");
  northing.text["axis"] = "Y";
  const std::vector<TestVar> vars = {
      coordinate("t", {1.0, 2.5}, "min"), coordinate("x", linspace(-3.0, 2.0, nx), "m"), northing,
      coordinate("z", linspace(0.0, 2.0, nz), "metres"),
      TestVar{"smoke", NC_DOUBLE, {"northing", "t", "x", "z"}, c, {{"units", "kg m-3"}}, {}}};
  // "t" is not a recognised name: it needs axis = "T".
  std::vector<TestVar> with_axis = vars;
  with_axis[0].text["axis"] = "T";
  const fs::path path = dir_ / "permuted.nc";
  make_netcdf(path, {{"northing", ny}, {"t", nt}, {"x", nx}, {"z", nz}}, with_axis);
  NetcdfReadOptions options;
  options.concentration = "smoke";
  const ConcentrationSeries s = read_netcdf_cf(path, options);
  ASSERT_EQ(s.frames.size(), nt);
  EXPECT_EQ(s.frames[0].time_s, 60.0);
  EXPECT_EQ(s.frames[1].time_s, 150.0);
  const ScalarGrid& g = s.frames[1].concentration_g_m3;
  ASSERT_EQ(g.dims, (GridDims{4, 3, 2}));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i)
        EXPECT_FLOAT_EQ(g.at(i, j, k), static_cast<float>(i + 10 * j + 100 * k + 1000))
            << i << j << k;
  EXPECT_NEAR(g.placement.voxel_size_m, 2.0, 1e-9);
  EXPECT_NEAR(g.placement.origin_m.x, -4.0, 1e-9);
  EXPECT_NEAR(g.placement.origin_m.y, 1999.0, 1e-9);  // southernmost centre 2000 m − 1 m
  EXPECT_NEAR(g.placement.origin_m.z, -1.0, 1e-9);

  const fs::path unnamed = dir_ / "unnamed.nc";
  make_netcdf(unnamed, {{"northing", ny}, {"t", nt}, {"x", nx}, {"z", nz}}, vars);
  const InputError e = expect_input_error([&] { read_netcdf_cf(unnamed, options); });
  EXPECT_EQ(e.field(), "smoke");
  EXPECT_TRUE(contains(e.detail(), "dimension 't' is not one of x, y, z, time")) << e.what();
}

TEST_F(NetcdfCfTest, PackedValuesAndTemperatureInCelsius) {
  const fs::path path = small_file("packed.nc", [](std::vector<TestVar>& vars) {
    TestVar& c = var(vars, "concentration");
    c.type = NC_SHORT;
    c.numbers = {{"scale_factor", 0.5}, {"add_offset", 1.0}};
    c.text["units"] = "mg/m3";
    for (double& v : c.data) v = std::fmod(v, 100.0);  // fits in a short
    TestVar t = c;
    t.name = "T";
    t.type = NC_FLOAT;
    t.numbers.clear();
    t.text["units"] = "degC";
    for (double& v : t.data) v = 20.0;
    vars.push_back(t);
  });
  NetcdfReadOptions options;
  options.temperature = "T";
  const ConcentrationSeries s = read_netcdf_cf(path, options);
  const ScalarGrid& g = s.frames[1].concentration_g_m3;
  // raw = (3 + 20 + 100 + 1000) mod 100 = 23 → (23·0.5 + 1) mg/m³.
  EXPECT_FLOAT_EQ(g.at(3, 2, 1), static_cast<float>((23 * 0.5 + 1.0) * 1e-3));
  ASSERT_TRUE(s.frames[1].temperature_k.has_value());
  EXPECT_FLOAT_EQ(s.frames[1].temperature_k->at(0, 0, 0), 293.15f);
}

TEST_F(NetcdfCfTest, FillValuesAreErrorsOrZero) {
  const fs::path path = small_file("fill.nc", [](std::vector<TestVar>& vars) {
    TestVar& c = var(vars, "concentration");
    c.numbers["_FillValue"] = -999.0;
    c.data[24 + 1 + 4 * 2] = -999.0;  // t = 1, voxel (1, 2, 0)
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(path); });
  EXPECT_EQ(e.field(), "concentration[time=1] voxel (1,2,0)");
  EXPECT_TRUE(contains(e.detail(), "missing value")) << e.what();
  NetcdfReadOptions options;
  options.missing_concentration_as_zero = true;
  const ConcentrationSeries s = read_netcdf_cf(path, options);
  EXPECT_EQ(s.frames[1].concentration_g_m3.at(1, 2, 0), 0.0f);
  EXPECT_EQ(s.frames[1].concentration_g_m3.at(2, 2, 0), 1022.0f);

  // Values never written carry netCDF's default fill value: missing too.
  const fs::path unwritten = small_file("unwritten.nc", [](std::vector<TestVar>& vars) {
    var(vars, "concentration").data.resize(24);  // only t = 0 written...
  });
  // ...but the unlimited time dimension is as long as the time coordinate (2).
  const InputError u = expect_input_error([&] { read_netcdf_cf(unwritten); });
  EXPECT_EQ(u.field(), "concentration[time=1] voxel (0,0,0)");
}

TEST_F(NetcdfCfTest, NanAndNegativeNameTheVoxel) {
  const fs::path nan = small_file("nan.nc", [](std::vector<TestVar>& vars) {
    var(vars, "concentration").data[2 + 4 * 1 + 12 * 1] = std::nan("");  // t=0, (2,1,1)
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(nan); });
  EXPECT_EQ(e.field(), "concentration[time=0] voxel (2,1,1)");
  EXPECT_TRUE(contains(e.detail(), "finite")) << e.what();
  const fs::path neg = small_file("neg.nc", [](std::vector<TestVar>& vars) {
    var(vars, "concentration").data[24 + 3] = -0.5;  // t=1, (3,0,0)
  });
  const InputError n = expect_input_error([&] { read_netcdf_cf(neg); });
  EXPECT_EQ(n.field(), "concentration[time=1] voxel (3,0,0)");
}

TEST_F(NetcdfCfTest, MissingVariableListsWhatExists) {
  const fs::path path = small_file("vars.nc");
  NetcdfReadOptions options;
  options.concentration = "soot";
  const InputError e = expect_input_error([&] { read_netcdf_cf(path, options); });
  EXPECT_EQ(e.field(), "soot");
  EXPECT_TRUE(contains(e.detail(), "no variable named 'soot'")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "time, z, y, x, concentration")) << e.what();
  options.concentration = "concentration";
  options.temperature = "T";
  const InputError t = expect_input_error([&] { read_netcdf_cf(path, options); });
  EXPECT_EQ(t.field(), "T");
}

TEST_F(NetcdfCfTest, WrongUnits) {
  const fs::path ratio = small_file("ratio.nc", [](std::vector<TestVar>& vars) {
    var(vars, "concentration").text["units"] = "kg kg-1";
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(ratio); });
  EXPECT_EQ(e.field(), "concentration:units");
  EXPECT_TRUE(contains(e.detail(), "'kg kg-1' is not a mass concentration")) << e.what();

  const fs::path none = small_file("none.nc", [](std::vector<TestVar>& vars) {
    var(vars, "concentration").text.erase("units");
  });
  EXPECT_EQ(expect_input_error([&] { read_netcdf_cf(none); }).field(), "concentration:units");
  NetcdfReadOptions options;
  options.concentration_units_if_missing = "kg m-3";
  EXPECT_EQ(read_netcdf_cf(none, options).frames[0].concentration_g_m3.at(1, 0, 0), 1000.0f);

  const fs::path feet = small_file(
      "feet.nc", [](std::vector<TestVar>& vars) { var(vars, "y").text["units"] = "ft"; });
  EXPECT_EQ(expect_input_error([&] { read_netcdf_cf(feet); }).field(), "y:units");
  const fs::path days = small_file("bad_time.nc", [](std::vector<TestVar>& vars) {
    var(vars, "time").text["units"] = "fortnights";
  });
  EXPECT_EQ(expect_input_error([&] { read_netcdf_cf(days); }).field(), "time:units");
}

TEST_F(NetcdfCfTest, NonUniformAndNonIsotropicCoordinates) {
  const fs::path uneven = small_file("uneven.nc", [](std::vector<TestVar>& vars) {
    var(vars, "x").data = {1.0, 1.5, 2.1, 2.5};
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(uneven); });
  EXPECT_EQ(e.field(), "x[2]");
  EXPECT_TRUE(contains(e.detail(), "not evenly spaced")) << e.what();

  const fs::path aniso = small_file("aniso.nc", [](std::vector<TestVar>& vars) {
    var(vars, "z").data = {3.0, 4.0};
  });
  const InputError a = expect_input_error([&] { read_netcdf_cf(aniso); });
  EXPECT_EQ(a.field(), "z");
  EXPECT_TRUE(contains(a.detail(), "cubic voxels")) << a.what();

  // Float coordinates far from 0 are accepted despite their rounding.
  const fs::path far = small_file("far.nc", [](std::vector<TestVar>& vars) {
    for (const char* n : {"x", "y", "z"}) {
      TestVar& v = var(vars, n);
      v.type = NC_FLOAT;
      for (double& c : v.data) c += 5000.1;
    }
  });
  EXPECT_NEAR(read_netcdf_cf(far).frames[0].concentration_g_m3.placement.voxel_size_m, 0.5, 1e-3);
}

TEST_F(NetcdfCfTest, UnsortedTimes) {
  const fs::path path = small_file("times.nc", [](std::vector<TestVar>& vars) {
    var(vars, "time").data = {30.0, 30.0};
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(path); });
  EXPECT_EQ(e.field(), "time[1]");
  EXPECT_TRUE(contains(e.detail(), "strictly increasing")) << e.what();
}

TEST_F(NetcdfCfTest, WrongDimensions) {
  const fs::path three = small_file("three.nc", [](std::vector<TestVar>& vars) {
    TestVar& c = var(vars, "concentration");
    c.dims = {"z", "y", "x"};
    c.data.resize(24);
  });
  const InputError e = expect_input_error([&] { read_netcdf_cf(three); });
  EXPECT_EQ(e.field(), "concentration");
  EXPECT_TRUE(contains(e.detail(), "has 3 dimensions (z, y, x); expected 4")) << e.what();

  // A temperature on other dimensions than the concentration's.
  const fs::path other = small_file("other.nc", [](std::vector<TestVar>& vars) {
    TestVar t = var(vars, "concentration");
    t.name = "T";
    t.dims = {"time", "z", "nv", "x"};
    t.data.clear();
    t.text["units"] = "K";
    vars.push_back(t);
  });
  NetcdfReadOptions options;
  options.temperature = "T";
  const InputError t = expect_input_error([&] { read_netcdf_cf(other, options); });
  EXPECT_EQ(t.field(), "T");
  EXPECT_TRUE(contains(t.detail(), "not those of the concentration variable")) << t.what();

  // One point along an axis gives no spacing.
  const fs::path flat = dir_ / "flat.nc";
  make_netcdf(flat, {{"time", 1}, {"z", 1}, {"y", 2}, {"x", 2}},
              {coordinate("time", {0.0}, "s"), coordinate("z", {0.0}, "m"),
               coordinate("y", {0.0, 1.0}, "m"), coordinate("x", {0.0, 1.0}, "m"),
               TestVar{"concentration",
                       NC_FLOAT,
                       {"time", "z", "y", "x"},
                       {0, 0, 0, 0},
                       {{"units", "g m-3"}},
                       {}}});
  const InputError f = expect_input_error([&] { read_netcdf_cf(flat); });
  EXPECT_EQ(f.field(), "z");
  EXPECT_TRUE(contains(f.detail(), "at least 2")) << f.what();
}

TEST_F(NetcdfCfTest, HugeDimensionsRefusedBeforeAllocating) {
  // netCDF-4 stores only chunks that are written: the file is small, its
  // header claims 10^15 voxels.
  const fs::path path = dir_ / "huge.nc";
  make_netcdf(
      path, {{"time", 1}, {"z", 100000}, {"y", 100000}, {"x", 100000}},
      {coordinate("time", {0.0}, "s"), coordinate("z", {}, "m"), coordinate("y", {}, "m"),
       coordinate("x", {}, "m"),
       TestVar{"concentration", NC_FLOAT, {"time", "z", "y", "x"}, {}, {{"units", "g m-3"}}, {}}});
  EXPECT_LT(fs::file_size(path), 1u << 20);
  const InputError e = expect_input_error([&] { read_netcdf_cf(path); });
  EXPECT_EQ(e.field(), "concentration");
  EXPECT_TRUE(contains(e.detail(), "GiB of memory is available")) << e.what();
}

TEST_F(NetcdfCfTest, NonExistentAndNonNetcdfFiles) {
  const fs::path missing = dir_ / "nope.nc";
  const InputError e = expect_input_error([&] { read_netcdf_cf(missing); });
  EXPECT_EQ(e.file(), missing.string());
  EXPECT_EQ(e.detail(), "file not found");
  const fs::path text = dir_ / "text.nc";
  std::ofstream(text) << "not netcdf\n";
  const InputError t = expect_input_error([&] { read_netcdf_cf(text); });
  EXPECT_TRUE(contains(t.detail(), "not a readable netCDF file")) << t.what();
}

TEST_F(NetcdfCfTest, WriterRefusesBadSeriesAndLeavesNothing) {
  const fs::path path = dir_ / "out.nc";
  ConcentrationSeries s;
  EXPECT_THROW(write_netcdf_cf(path, s), InputError);  // no frames
  ConcentrationFrame a;
  a.concentration_g_m3 = random_grid(1, 0.0f, 1.0f);
  ConcentrationFrame b = a;
  s.frames = {a, b};  // equal times
  EXPECT_THROW(write_netcdf_cf(path, s), InputError);
  s.frames[1].time_s = 1.0;
  s.frames[1].concentration_g_m3.placement.voxel_size_m = 0.5;  // another grid
  EXPECT_THROW(write_netcdf_cf(path, s), InputError);
  s.frames[1].concentration_g_m3.placement.voxel_size_m = 0.75;
  s.frames[1].temperature_k = s.frames[1].concentration_g_m3;  // temperature in one frame only
  EXPECT_THROW(write_netcdf_cf(path, s), InputError);
  EXPECT_TRUE(dir_entries().empty());
}

}  // namespace
}  // namespace obscura
