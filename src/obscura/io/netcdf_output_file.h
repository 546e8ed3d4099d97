#pragma once
// A netCDF-4 file written piece by piece and put in place atomically: it is
// created under a temporary name (io/atomic_file.h) and stays open between
// calls, so a writer can define its dimensions and variables, write a
// record at a time as the data arrives (a render's frames), define more
// variables later (redefine) and, once the file is complete, rename it over
// its final name (commit). Destroyed without commit(), the temporary is
// closed and removed; a killed run's temporary is removed by the next run in
// the folder (io/stale_temporaries.h).
//
// netCDF-C stays inside: dimensions and variables are plain ids, types an
// enum. Every call holds the netCDF lock (io/netcdf_file.h). Failures throw
// obscura::Error naming the final file and what was being written.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "obscura/io/atomic_file.h"

namespace obscura {

// The value types of the variables and attributes this writer makes
// (netCDF-4 NC_UBYTE, NC_INT, NC_UINT64, NC_FLOAT, NC_DOUBLE, NC_STRING).
enum class NcType { kUByte, kInt, kUInt64, kFloat, kDouble, kString };

class NetcdfOutputFile {
 public:
  // The id of the file's global attributes (netCDF's NC_GLOBAL).
  static constexpr int kGlobal = -1;
  // A dimension length that grows as records are written (netCDF's NC_UNLIMITED).
  static constexpr std::size_t kUnlimited = 0;

  // Creates the temporary file (netCDF-4, in define mode).
  explicit NetcdfOutputFile(std::filesystem::path final_path);
  ~NetcdfOutputFile();
  NetcdfOutputFile(const NetcdfOutputFile&) = delete;
  NetcdfOutputFile& operator=(const NetcdfOutputFile&) = delete;

  // Definitions: in define mode (after creation, or after redefine()).
  int define_dimension(const std::string& name, std::size_t length);
  // `chunk`: a chunk size per dimension (empty: netCDF's default layout);
  // `compress`: zlib level 1 with the shuffle filter (needs `chunk`). The
  // variable's chunk cache is kept small, so a write of whole chunks goes
  // straight to the file and memory stays about one chunk per write.
  int define_variable(const std::string& name, NcType type, const std::vector<int>& dims,
                      const std::vector<std::size_t>& chunk = {}, bool compress = false);
  void put_attribute(int var, const std::string& name, std::string_view text);
  void put_attribute(int var, const std::string& name, const std::vector<double>& values);
  void put_attribute(int var, const std::string& name, const std::vector<int>& values);
  void put_attribute(int var, const std::string& name, const std::vector<std::uint8_t>& values);
  void put_attribute(int var, const std::string& name, std::uint64_t value);
  void end_definitions();
  void redefine();

  // Values of the hyperslab start[i] … start[i] + count[i] − 1, C order (the
  // last dimension fastest). Writable in either mode (netCDF-4 switches).
  void put(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count,
           const float* values);
  void put(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count,
           const double* values);
  void put(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count,
           const int* values);
  void put(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count,
           const std::uint8_t* values);
  void put(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count,
           const std::vector<std::string>& values);

  // The current length of a dimension (of an unlimited one: records written).
  std::size_t dimension_length(int dim) const;

  // Closes the file and renames it over the final path.
  void commit();
  bool committed() const { return atomic_.committed(); }
  const std::filesystem::path& final_path() const { return atomic_.final_path(); }

 private:
  void check(int status, std::string_view doing) const;

  AtomicFile atomic_;
  int ncid_ = -1;
};

}  // namespace obscura
