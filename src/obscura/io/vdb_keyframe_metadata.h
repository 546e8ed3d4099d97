#pragma once
// The file-level metadata of a cloud-keyframe file (io/vdb_keyframe.h,
// docs/formats.md): typed access whose errors name the field, the header both
// forms share (format, version, form, time, wavelengths, dims), as read and
// as written, and the checks of the caller's extra metadata. Internal to io/.
#include <openvdb/openvdb.h>

#include <map>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vdb_format {

// Wavelengths as "w0,w1,..." with 17 significant digits (round-trip any
// double), and back; parse_wavelengths throws InputError naming `file`.
std::string format_wavelengths(const std::vector<double>& w);
std::vector<double> parse_wavelengths(const std::string& text, const std::string& file);

// Typed access to file metadata with errors that name the field.
class MetaReader {
 public:
  MetaReader(const openvdb::MetaMap& meta, std::string file)
      : meta_(meta), file_(std::move(file)) {}

  std::string get_string(const std::string& key) const;
  // Accepts 32- and 64-bit integers: pyopenvdb writes Python ints as int64.
  long long get_int(const std::string& key) const;
  double get_double(const std::string& key) const;
  openvdb::Vec3i get_vec3i(const std::string& key) const;

 private:
  openvdb::Metadata::ConstPtr require(const std::string& key) const;
  InputError wrong_type(const std::string& key, const openvdb::Metadata::ConstPtr& m,
                        const char* expected) const;

  const openvdb::MetaMap& meta_;
  std::string file_;
};

// The metadata both forms share, read and checked.
struct CommonHeader {
  std::string form;
  double time_s = 0.0;
  std::vector<double> wavelengths_um;
  GridDims dims;
};

CommonHeader read_common_header(const MetaReader& meta, const openvdb::MetaMap& map,
                                const std::string& file);

// The string metadata `key` must be `want`.
void require_units(const MetaReader& meta, const std::string& key, const char* want,
                   const std::string& file);

// A time the writer accepts (finite, >= 0) and extra metadata that uses no
// reserved key.
void check_time_and_metadata(const std::string& file, double time_s,
                             const std::map<std::string, std::string>& extra_metadata);

// The file metadata both forms carry.
openvdb::MetaMap common_metadata(const char* form, double time_s,
                                 const std::vector<double>& wavelengths_um, const GridDims& d,
                                 const GridPlacement& placement,
                                 const std::map<std::string, std::string>& extra_metadata);

}  // namespace obscura::vdb_format
