#pragma once
// Access to the netCDF-C library for the CF reader and writer
// (io/netcdf_cf.h): the lock every call must hold, a handle that closes the
// file, and typed reads of names, dimensions and attributes whose errors name
// the file and the variable. Internal to io/.
#include <netcdf.h>

#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::netcdf_cf {

// The netCDF-C library is not thread-safe (netCDF FAQ, "Is netCDF
// thread-safe?"): every call into it holds this lock.
std::mutex& netcdf_mutex();

// Closes the file on every exit path.
struct NcHandle {
  int id = -1;
  NcHandle() = default;
  NcHandle(const NcHandle&) = delete;
  NcHandle& operator=(const NcHandle&) = delete;
  ~NcHandle() {
    if (id >= 0) nc_close(id);
  }
  int release() {
    const int r = id;
    id = -1;
    return r;
  }
};

bool is_numeric_type(nc_type t);

// Relative precision of a coordinate as stored: the uniformity test must not
// fail on float rounding of, e.g., x = 1000.1, 1000.2, ...
double storage_epsilon(nc_type t);

// Reads from an open file; every failure is an InputError naming `file` and
// the variable or attribute.
class NcReader {
 public:
  NcReader(std::string file, int ncid) : file_(std::move(file)), ncid_(ncid) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  void check(int status, const std::string& field, std::string_view doing) const;

  std::string var_name(int varid) const;
  std::string dim_name(int dimid) const;
  std::size_t dim_len(int dimid) const;
  // "variables in the file: a, b, c", for "no variable named ...".
  std::string variable_list() const;
  int find_variable(const std::string& name) const;
  std::vector<int> var_dims(int varid) const;
  nc_type var_type(int varid) const;

  // A text attribute (NC_CHAR, or a single NC_STRING as netCDF-4 tools may
  // write); nullopt if absent.
  std::optional<std::string> text_attribute(int varid, const char* att) const;
  // A numeric attribute as doubles (missing_value may be a vector, CF §2.5.1);
  // empty if absent.
  std::vector<double> number_attribute(int varid, const char* att) const;
  // The n values of a 1-D variable.
  std::vector<double> read_1d(int varid, std::size_t n) const;

  int ncid() const { return ncid_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  int ncid_;
};

}  // namespace obscura::netcdf_cf
