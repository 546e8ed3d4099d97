#include "obscura/io/netcdf_output_file.h"

#include <fmt/format.h>

#include <mutex>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/io/netcdf_file.h"

namespace obscura {
namespace {

static_assert(NetcdfOutputFile::kGlobal == NC_GLOBAL);
static_assert(NetcdfOutputFile::kUnlimited == NC_UNLIMITED);

nc_type to_nc(NcType t) {
  switch (t) {
    case NcType::kUByte:
      return NC_UBYTE;
    case NcType::kInt:
      return NC_INT;
    case NcType::kUInt64:
      return NC_UINT64;
    case NcType::kFloat:
      return NC_FLOAT;
    case NcType::kDouble:
      return NC_DOUBLE;
    case NcType::kString:
      return NC_STRING;
  }
  return NC_NAT;
}

// The chunk cache of every variable: a whole-chunk write larger than this
// bypasses the cache (HDF5 writes it through), so a file with many large
// image variables does not hold a cached chunk of each (netCDF's default is
// 16–64 MiB per variable).
constexpr std::size_t kChunkCacheBytes = std::size_t{1} << 20;
constexpr std::size_t kChunkCacheSlots = 101;
constexpr float kChunkCachePreemption = 0.75f;

std::string describe(const std::string& what, const std::string& name) {
  return name.empty() ? what : what + " " + name;
}

}  // namespace

NetcdfOutputFile::NetcdfOutputFile(std::filesystem::path final_path)
    : atomic_(std::move(final_path)) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  int id = -1;
  const int status = nc_create(atomic_.temp_path().c_str(), NC_NETCDF4 | NC_CLOBBER, &id);
  if (status != NC_NOERR)
    throw Error(fmt::format("cannot create {} (as {}): {}", atomic_.final_path().string(),
                            atomic_.temp_path().string(), nc_strerror(status)));
  ncid_ = id;
}

NetcdfOutputFile::~NetcdfOutputFile() {
  if (ncid_ < 0) return;
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  nc_close(ncid_);  // the AtomicFile then removes the temporary
}

void NetcdfOutputFile::check(int status, std::string_view doing) const {
  if (status != NC_NOERR)
    throw Error(fmt::format("cannot write {}: {}: {}", atomic_.final_path().string(), doing,
                            nc_strerror(status)));
}

int NetcdfOutputFile::define_dimension(const std::string& name, std::size_t length) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  int id = -1;
  check(nc_def_dim(ncid_, name.c_str(), length, &id), describe("dimension", name));
  return id;
}

int NetcdfOutputFile::define_variable(const std::string& name, NcType type,
                                      const std::vector<int>& dims,
                                      const std::vector<std::size_t>& chunk, bool compress) {
  OBSCURA_CHECK(chunk.empty() || chunk.size() == dims.size());
  OBSCURA_CHECK(!compress || !chunk.empty());
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  const std::string what = describe("variable", name);
  int id = -1;
  check(
      nc_def_var(ncid_, name.c_str(), to_nc(type), static_cast<int>(dims.size()), dims.data(), &id),
      what);
  if (!chunk.empty()) {
    check(nc_def_var_chunking(ncid_, id, NC_CHUNKED, chunk.data()), what + " chunking");
    check(nc_set_var_chunk_cache(ncid_, id, kChunkCacheBytes, kChunkCacheSlots,
                                 kChunkCachePreemption),
          what + " chunk cache");
  }
  if (compress) check(nc_def_var_deflate(ncid_, id, 1, 1, 1), what + " compression");
  return id;
}

void NetcdfOutputFile::put_attribute(int var, const std::string& name, std::string_view text) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_att_text(ncid_, var, name.c_str(), text.size(), text.data()),
        describe("attribute", name));
}

void NetcdfOutputFile::put_attribute(int var, const std::string& name,
                                     const std::vector<double>& values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_att_double(ncid_, var, name.c_str(), NC_DOUBLE, values.size(), values.data()),
        describe("attribute", name));
}

void NetcdfOutputFile::put_attribute(int var, const std::string& name,
                                     const std::vector<int>& values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_att_int(ncid_, var, name.c_str(), NC_INT, values.size(), values.data()),
        describe("attribute", name));
}

void NetcdfOutputFile::put_attribute(int var, const std::string& name,
                                     const std::vector<std::uint8_t>& values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_att_uchar(ncid_, var, name.c_str(), NC_UBYTE, values.size(), values.data()),
        describe("attribute", name));
}

void NetcdfOutputFile::put_attribute(int var, const std::string& name, std::uint64_t value) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  const unsigned long long v = value;
  check(nc_put_att_ulonglong(ncid_, var, name.c_str(), NC_UINT64, 1, &v),
        describe("attribute", name));
}

void NetcdfOutputFile::end_definitions() {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_enddef(ncid_), "end of definitions");
}

void NetcdfOutputFile::redefine() {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_redef(ncid_), "back to define mode");
}

void NetcdfOutputFile::put(int var, const std::vector<std::size_t>& start,
                           const std::vector<std::size_t>& count, const float* values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_vara_float(ncid_, var, start.data(), count.data(), values), "float values");
}

void NetcdfOutputFile::put(int var, const std::vector<std::size_t>& start,
                           const std::vector<std::size_t>& count, const double* values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_vara_double(ncid_, var, start.data(), count.data(), values), "double values");
}

void NetcdfOutputFile::put(int var, const std::vector<std::size_t>& start,
                           const std::vector<std::size_t>& count, const int* values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_vara_int(ncid_, var, start.data(), count.data(), values), "int values");
}

void NetcdfOutputFile::put(int var, const std::vector<std::size_t>& start,
                           const std::vector<std::size_t>& count, const std::uint8_t* values) {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_vara_uchar(ncid_, var, start.data(), count.data(), values), "byte values");
}

void NetcdfOutputFile::put(int var, const std::vector<std::size_t>& start,
                           const std::vector<std::size_t>& count,
                           const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& v : values) pointers.push_back(v.c_str());
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  check(nc_put_vara_string(ncid_, var, start.data(), count.data(), pointers.data()),
        "string values");
}

std::size_t NetcdfOutputFile::dimension_length(int dim) const {
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  std::size_t length = 0;
  check(nc_inq_dimlen(ncid_, dim, &length), "dimension length");
  return length;
}

void NetcdfOutputFile::commit() {
  {
    std::lock_guard lock(netcdf_cf::netcdf_mutex());
    const int id = ncid_;
    ncid_ = -1;  // closed (or unusable) whatever nc_close says
    check(nc_close(id), "close");
  }
  atomic_.commit();
}

}  // namespace obscura
