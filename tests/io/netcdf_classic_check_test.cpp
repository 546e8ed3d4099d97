// The classic-format header walk before nc_open (io/netcdf_classic_check.h).
// Truth is netCDF-C: every classic file it writes (CDF-1, CDF-2, CDF-5, with
// and without record variables) passes the walk, and the corruptions that
// made nc_open allocate what the header said are refused first.
#include "obscura/io/netcdf_classic_check.h"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "support/file_bytes.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;
using testing::Bytes;

void ok(int status) { ASSERT_EQ(status, NC_NOERR) << nc_strerror(status); }

class NetcdfClassicCheckTest : public testing::TempDirTest {
 protected:
  // A file with a record dimension, `record_vars` record variables of three
  // bytes per record (the padding case), fixed variables of several types,
  // and global and variable attributes.
  fs::path write(int mode, int record_vars, std::size_t records) {
    const fs::path p = dir_ / ("f" + std::to_string(counter_++) + ".nc");
    int nc = -1, t = -1, x = -1, y = -1;
    ok(nc_create(p.c_str(), NC_CLOBBER | mode, &nc));
    ok(nc_def_dim(nc, "time", NC_UNLIMITED, &t));
    ok(nc_def_dim(nc, "x", 3, &x));
    ok(nc_def_dim(nc, "y", 5, &y));
    ok(nc_put_att_text(nc, NC_GLOBAL, "Conventions", 6, "CF-1.8"));
    const double range[2] = {0.0, 1.0};
    ok(nc_put_att_double(nc, NC_GLOBAL, "range", NC_DOUBLE, 2, range));
    int fixed = -1, shorts = -1;
    const int xy[2] = {x, y};
    ok(nc_def_var(nc, "fixed", NC_DOUBLE, 2, xy, &fixed));
    ok(nc_put_att_text(nc, fixed, "units", 5, "kg/m3"));
    ok(nc_def_var(nc, "shorts", NC_SHORT, 1, &y, &shorts));
    std::vector<int> rec(static_cast<std::size_t>(record_vars));
    const int tx[2] = {t, x};
    for (int v = 0; v < record_vars; ++v)
      ok(nc_def_var(nc, ("rec" + std::to_string(v)).c_str(), NC_BYTE, 2, tx,
                    &rec[static_cast<std::size_t>(v)]));
    ok(nc_enddef(nc));
    std::vector<double> f(15, 2.5);
    ok(nc_put_var_double(nc, fixed, f.data()));
    const short s[5] = {1, 2, 3, 4, 5};
    ok(nc_put_var_short(nc, shorts, s));
    for (int v = 0; v < record_vars; ++v)
      for (std::size_t r = 0; r < records; ++r) {
        const std::size_t start[2] = {r, 0}, count[2] = {1, 3};
        const signed char b[3] = {1, 2, 3};
        ok(nc_put_vara_schar(nc, rec[static_cast<std::size_t>(v)], start, count, b));
      }
    ok(nc_close(nc));
    return p;
  }

  // The message of the InputError the check must throw.
  static std::string refusal(const fs::path& p) {
    return testing::expect_input_error([&] { netcdf_cf::check_netcdf_classic_header(p); }).what();
  }

  int counter_ = 0;
};

TEST_F(NetcdfClassicCheckTest, EveryClassicLayoutNetcdfWritesIsAccepted) {
  for (const int mode : {0, NC_64BIT_OFFSET, NC_64BIT_DATA})
    for (const int record_vars : {0, 1, 3})
      for (const std::size_t records : {std::size_t{0}, std::size_t{1}, std::size_t{4}}) {
        SCOPED_TRACE(::testing::Message() << "mode " << mode << " record variables " << record_vars
                                          << " records " << records);
        const fs::path p = write(mode, record_vars, records);
        EXPECT_NO_THROW(netcdf_cf::check_netcdf_classic_header(p));
        int nc = -1;
        EXPECT_EQ(nc_open(p.c_str(), NC_NOWRITE, &nc), NC_NOERR);
        nc_close(nc);
      }
}

TEST_F(NetcdfClassicCheckTest, ANetcdf4FileIsLeftToHdf5) {
  const fs::path p = write(NC_NETCDF4, 1, 2);
  EXPECT_NO_THROW(netcdf_cf::check_netcdf_classic_header(p));
}

TEST_F(NetcdfClassicCheckTest, EveryTruncationIsRefused) {
  for (const int mode : {0, NC_64BIT_DATA}) {
    const Bytes b = testing::read_file_bytes(write(mode, 3, 4));
    // netCDF-C may pad the last record to 4 bytes, which a reader does not need.
    for (std::size_t len = 4; len + 4 < b.size(); ++len) {  // shorter: no magic, not classic
      testing::write_file_bytes(dir_ / "cut.nc",
                                Bytes(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(len)));
      EXPECT_NE(refusal(dir_ / "cut.nc"), "")
          << "mode " << mode << " cut at " << len << " of " << b.size();
    }
  }
}

TEST_F(NetcdfClassicCheckTest, AHugeNameLengthIsRefusedBeforeNetcdfAllocatesIt) {
  // The fuzzing finding: new_NC_string calloc'ed 3.1 GB for a name length.
  Bytes b = testing::read_file_bytes(write(0, 1, 1));
  const std::string key = "Conventions";
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  ASSERT_NE(it, b.end());
  const std::size_t len_at = static_cast<std::size_t>(it - b.begin()) - 4;  // big-endian uint32
  ASSERT_EQ(b[len_at + 3], static_cast<char>(key.size()));
  b[len_at] = static_cast<char>(0xB9);
  testing::write_file_bytes(dir_ / "name.nc", b);
  const std::string msg = refusal(dir_ / "name.nc");
  EXPECT_NE(msg.find("global attributes"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a name of 3103784971 bytes"), std::string::npos) << msg;
}

TEST_F(NetcdfClassicCheckTest, CountsBeyondTheFileAreRefused) {
  Bytes b = testing::read_file_bytes(write(0, 1, 1));
  // The dimension list: magic (4), numrecs (4), NC_DIMENSION tag (4), count.
  ASSERT_EQ(b[11], 0x0A);
  b[12] = 0x7F;
  testing::write_file_bytes(dir_ / "dims.nc", b);
  const std::string msg = refusal(dir_ / "dims.nc");
  EXPECT_NE(msg.find("dimensions: claims 2130706435 entries"), std::string::npos) << msg;
}

TEST_F(NetcdfClassicCheckTest, AnUnknownVersionByteIsNamed) {
  Bytes b = testing::read_file_bytes(write(0, 0, 0));
  b[3] = 7;
  testing::write_file_bytes(dir_ / "v.nc", b);
  EXPECT_NE(refusal(dir_ / "v.nc").find("version byte 7"), std::string::npos);
}

}  // namespace
}  // namespace obscura
