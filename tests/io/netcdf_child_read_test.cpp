#include "obscura/io/netcdf_child_read.h"

#include <gtest/gtest.h>
#include <netcdf.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/io/netcdf_cf.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura::netcdf_cf {
namespace {

namespace fs = std::filesystem;
using obscura::testing::contains;
using obscura::testing::expect_input_error;

class NetcdfChildReadTest : public obscura::testing::TempDirTest {};

ConcentrationSeries two_frames() {
  ConcentrationSeries s;
  s.source = "made by the test";
  for (int t = 0; t < 2; ++t) {
    ConcentrationFrame f;
    f.time_s = 2.5 * t;
    f.concentration_g_m3.dims = {3, 2, 1};
    f.concentration_g_m3.placement.origin_m = {-1.5, 2.25, 1e-3};
    f.concentration_g_m3.placement.voxel_size_m = 0.375;
    for (int i = 0; i < 6; ++i) f.concentration_g_m3.values.push_back(0.1f * i + t);
    if (t == 1) {
      ScalarGrid k = f.concentration_g_m3;
      for (float& v : k.values) v += 290.0f;
      f.temperature_k = k;
    }
    s.frames.push_back(f);
  }
  return s;
}

TEST_F(NetcdfChildReadTest, TheSeriesComesBackExactly) {
  const ConcentrationSeries sent = two_frames();
  const ConcentrationSeries got = read_in_child_process("f.nc", [&](const auto& header_read) {
    header_read();
    return sent;
  });
  EXPECT_EQ(got.source, sent.source);
  ASSERT_EQ(got.frames.size(), 2u);
  for (std::size_t t = 0; t < 2; ++t) {
    const ConcentrationFrame &a = sent.frames[t], &b = got.frames[t];
    EXPECT_EQ(b.time_s, a.time_s);
    EXPECT_EQ(b.concentration_g_m3.dims, a.concentration_g_m3.dims);
    EXPECT_EQ(b.concentration_g_m3.placement.origin_m, a.concentration_g_m3.placement.origin_m);
    EXPECT_EQ(b.concentration_g_m3.placement.voxel_size_m,
              a.concentration_g_m3.placement.voxel_size_m);
    EXPECT_EQ(b.concentration_g_m3.values, a.concentration_g_m3.values);
    ASSERT_EQ(b.temperature_k.has_value(), a.temperature_k.has_value());
    if (a.temperature_k) {
      EXPECT_EQ(b.temperature_k->values, a.temperature_k->values);
    }
  }
}

TEST_F(NetcdfChildReadTest, TheChildsErrorsKeepTheirKindAndFields) {
  const InputError e = expect_input_error([] {
    read_in_child_process("f.nc", [](const auto&) -> ConcentrationSeries {
      throw InputError("f.nc", "concentration:units", "'ppm' is not a mass concentration");
    });
  });
  EXPECT_EQ(e.file(), "f.nc");
  EXPECT_EQ(e.field(), "concentration:units");
  EXPECT_EQ(e.detail(), "'ppm' is not a mass concentration");
  EXPECT_THROW(read_in_child_process(
                   "f.nc", [](const auto&) -> ConcentrationSeries { throw InternalError("bug"); }),
               InternalError);
  try {
    read_in_child_process("f.nc", [](const auto&) -> ConcentrationSeries {
      throw Error("out of memory: 3 GiB asked");
    });
    ADD_FAILURE() << "no error";
  } catch (const InputError&) {
    ADD_FAILURE() << "an Error came back as an InputError";
  } catch (const Error& other) {
    EXPECT_STREQ(other.what(), "out of memory: 3 GiB asked");
  }
}

TEST_F(NetcdfChildReadTest, AChildThatDiesIsAnInputErrorNamingTheFile) {
  // What HDF5 does on some corrupt files (the release build: SIGSEGV; under
  // AddressSanitizer the child reports and exits with its status instead).
  const InputError e = expect_input_error([] {
    read_in_child_process("f.nc", [](const auto&) -> ConcentrationSeries {
      ::raise(SIGSEGV);
      return {};
    });
  });
  EXPECT_EQ(e.file(), "f.nc");
  EXPECT_TRUE(contains(e.detail(), "the file is corrupt")) << e.what();
  const InputError x = expect_input_error([] {
    read_in_child_process("f.nc", [](const auto& header_read) -> ConcentrationSeries {
      header_read();
      ::_exit(7);
    });
  });
  EXPECT_TRUE(contains(x.detail(), "ended with exit status 7")) << x.what();
}

TEST_F(NetcdfChildReadTest, AChildStuckBeforeTheDataIsStopped) {
  // What HDF5 does on other corrupt files: loop forever reading the structure.
  const InputError e = expect_input_error([] {
    read_in_child_process(
        "f.nc",
        [](const auto&) -> ConcentrationSeries {
          for (;;) ::pause();
        },
        0.2);
  });
  EXPECT_EQ(e.file(), "f.nc");
  EXPECT_TRUE(contains(e.detail(), "after 0.2 s and was stopped")) << e.what();
}

TEST_F(NetcdfChildReadTest, TheDataHaveNoTimeLimit) {
  const ConcentrationSeries sent = two_frames();
  const ConcentrationSeries got = read_in_child_process(
      "f.nc",
      [&](const auto& header_read) {
        header_read();
        std::this_thread::sleep_for(std::chrono::milliseconds(600));  // 3 × the limit
        return sent;
      },
      0.2);
  EXPECT_EQ(got.frames.size(), 2u);
}

TEST_F(NetcdfChildReadTest, Hdf5ContainersAreRecognisedAsNetcdfCDoes) {
  const fs::path nc4 = dir_ / "a.nc", classic = dir_ / "b.nc";
  for (const auto& [path, mode] : {std::pair{nc4, NC_NETCDF4}, std::pair{classic, 0}}) {
    int id = -1;
    ASSERT_EQ(nc_create(path.c_str(), mode | NC_CLOBBER, &id), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
  }
  EXPECT_TRUE(is_hdf5_container(nc4));
  EXPECT_FALSE(is_hdf5_container(classic));
  // A user block before the superblock: HDF5 looks at 512, 1024, 2048, ...
  const std::string signature("\x89HDF\r\n\x1a\n", 8);
  const auto file_with_signature_at = [&](std::size_t offset, const std::string& start) {
    std::string bytes(4096, '\0');
    bytes.replace(0, start.size(), start);
    bytes.replace(offset, signature.size(), signature);
    const fs::path p = dir_ / ("at" + std::to_string(offset));
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  };
  EXPECT_TRUE(is_hdf5_container(file_with_signature_at(512, "user block")));
  EXPECT_TRUE(is_hdf5_container(file_with_signature_at(2048, "user block")));
  EXPECT_FALSE(is_hdf5_container(file_with_signature_at(513, "user block")));
  EXPECT_FALSE(is_hdf5_container(file_with_signature_at(512, "CDF\x01")));  // classic first
  EXPECT_FALSE(is_hdf5_container(dir_ / "missing.nc"));
}

TEST_F(NetcdfChildReadTest, ACorruptNetcdf4FileThatCrashesHdf5IsAnInputError) {
  // Found by fuzz/netcdf4_cf: a DIMENSION_LIST attribute whose global-heap
  // object HDF5 1.10.8 copies out of bounds (H5HG_read), reached from
  // nc_inq_varndims. In this process it was a SIGSEGV.
  const fs::path path = fs::path(OBSCURA_SOURCE_DIR) /
                        "fuzz/regressions/netcdf4_cf/hdf5-global-heap-read-out-of-bounds";
  const InputError e = expect_input_error([&] { read_netcdf_cf(path); });
  EXPECT_EQ(e.file(), path.string());
  EXPECT_TRUE(contains(e.detail(), "the file is corrupt")) << e.what();
}

}  // namespace
}  // namespace obscura::netcdf_cf
