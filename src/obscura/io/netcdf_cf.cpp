#include "obscura/io/netcdf_cf.h"

#include <fmt/format.h>
#include <netcdf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {
namespace {

// Coordinates are "evenly spaced" and "isotropic" to this relative tolerance.
constexpr double kUniformTolerance = 1e-6;

// The netCDF-C library is not thread-safe (netCDF FAQ, "Is netCDF
// thread-safe?"): every call into it from this file holds this lock.
std::mutex& netcdf_mutex() {
  static std::mutex m;
  return m;
}

enum Axis { kX = 0, kY = 1, kZ = 2, kT = 3 };
constexpr const char* kAxisNames[] = {"x", "y", "z", "time"};

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

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool is_numeric_type(nc_type t) {
  switch (t) {
    case NC_BYTE:
    case NC_UBYTE:
    case NC_SHORT:
    case NC_USHORT:
    case NC_INT:
    case NC_UINT:
    case NC_INT64:
    case NC_UINT64:
    case NC_FLOAT:
    case NC_DOUBLE:
      return true;
    default:
      return false;
  }
}

// Relative precision of a coordinate as stored: the uniformity test must not
// fail on float rounding of, e.g., x = 1000.1, 1000.2, ...
double storage_epsilon(nc_type t) {
  if (t == NC_FLOAT) return FLT_EPSILON;
  if (t == NC_DOUBLE) return 4 * DBL_EPSILON;
  return 0.0;
}

// ---------------------------------------------------------------------------
// Units (CF §3.1: UDUNITS strings). Only the spellings below are accepted;
// anything else is an error that names the attribute, never a guess.

std::optional<double> length_to_m(const std::string& units) {
  const std::string u = trim(units);
  for (const char* m : {"m", "metre", "meter", "metres", "meters"})
    if (u == m) return 1.0;
  for (const char* km : {"km", "kilometre", "kilometer", "kilometres", "kilometers"})
    if (u == km) return 1000.0;
  return std::nullopt;
}

// "UNIT" or "UNIT since REFERENCE" (CF §4.4). The reference time is not used:
// frame times are the coordinate values converted to seconds.
std::optional<double> time_to_s(const std::string& units) {
  std::string u = trim(units);
  const std::string l = lower(u);
  const auto since = l.find(" since ");
  const std::string unit = trim(since == std::string::npos ? l : l.substr(0, since));
  for (const char* s : {"s", "sec", "secs", "second", "seconds"})
    if (unit == s) return 1.0;
  for (const char* s : {"min", "mins", "minute", "minutes"})
    if (unit == s) return 60.0;
  for (const char* s : {"h", "hr", "hrs", "hour", "hours"})
    if (unit == s) return 3600.0;
  for (const char* s : {"d", "day", "days"})
    if (unit == s) return 86400.0;
  return std::nullopt;
}

// Mass per volume: "<mass> m-3", "<mass> m^-3", "<mass>/m3", "<mass>/m^3",
// with mass kg, g, mg, ug (or µg); spaces and '.' separators are ignored.
std::optional<double> concentration_to_g_m3(const std::string& units) {
  std::string u;
  for (char c : trim(units))
    if (c != ' ' && c != '.') u += c;
  for (const char* volume : {"m-3", "m^-3", "m**-3", "/m3", "/m^3", "/m**3"}) {
    const std::string v = volume;
    if (u.size() <= v.size() || u.compare(u.size() - v.size(), v.size(), v) != 0) continue;
    const std::string mass = u.substr(0, u.size() - v.size());
    if (mass == "kg") return 1000.0;
    if (mass == "g") return 1.0;
    if (mass == "mg") return 1e-3;
    if (mass == "ug" || mass == "\xC2\xB5g" || mass == "\xCE\xBCg") return 1e-6;
  }
  return std::nullopt;
}

// Offset to add to get kelvin.
std::optional<double> temperature_offset_to_k(const std::string& units) {
  const std::string u = trim(units);
  for (const char* k : {"K", "kelvin", "Kelvin", "degK", "degrees_K"})
    if (u == k) return 0.0;
  for (const char* c : {"degC", "deg_C", "celsius", "Celsius", "degree_Celsius", "degrees_Celsius",
                        "degree_C", "degrees_C"})
    if (u == c) return 273.15;
  return std::nullopt;
}

// ---------------------------------------------------------------------------
class NcReader {
 public:
  NcReader(std::string file, int ncid) : file_(std::move(file)), ncid_(ncid) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(file_, field, what);
  }
  void check(int status, const std::string& field, std::string_view doing) const {
    if (status != NC_NOERR) fail(field, fmt::format("{}: {}", doing, nc_strerror(status)));
  }

  std::string var_name(int varid) const {
    char name[NC_MAX_NAME + 1] = {};
    check(nc_inq_varname(ncid_, varid, name), "", "cannot read a variable name");
    return name;
  }
  std::string dim_name(int dimid) const {
    char name[NC_MAX_NAME + 1] = {};
    check(nc_inq_dimname(ncid_, dimid, name), "", "cannot read a dimension name");
    return name;
  }
  std::size_t dim_len(int dimid) const {
    std::size_t len = 0;
    check(nc_inq_dimlen(ncid_, dimid, &len), dim_name(dimid), "cannot read the dimension length");
    return len;
  }

  std::string variable_list() const {
    int n = 0;
    check(nc_inq_nvars(ncid_, &n), "", "cannot list variables");
    if (n == 0) return "the file has no variables";
    std::string s = "variables in the file: ";
    for (int v = 0; v < n; ++v) s += (v ? ", " : "") + var_name(v);
    return s;
  }

  int find_variable(const std::string& name) const {
    int varid = -1;
    const int status = nc_inq_varid(ncid_, name.c_str(), &varid);
    if (status == NC_ENOTVAR)
      fail(name, fmt::format("no variable named '{}'; {}", name, variable_list()));
    check(status, name, "cannot look up the variable");
    return varid;
  }

  std::vector<int> var_dims(int varid) const {
    int ndims = 0;
    check(nc_inq_varndims(ncid_, varid, &ndims), var_name(varid), "cannot read the dimensions");
    std::vector<int> dims(static_cast<std::size_t>(ndims));
    check(nc_inq_vardimid(ncid_, varid, dims.data()), var_name(varid),
          "cannot read the dimensions");
    return dims;
  }

  nc_type var_type(int varid) const {
    nc_type t = NC_NAT;
    check(nc_inq_vartype(ncid_, varid, &t), var_name(varid), "cannot read the type");
    return t;
  }

  // A text attribute (NC_CHAR, or a single NC_STRING as netCDF-4 tools may
  // write); nullopt if absent.
  std::optional<std::string> text_attribute(int varid, const char* att) const {
    const std::string field = var_name(varid) + ":" + att;
    nc_type type = NC_NAT;
    std::size_t len = 0;
    const int status = nc_inq_att(ncid_, varid, att, &type, &len);
    if (status == NC_ENOTATT) return std::nullopt;
    check(status, field, "cannot read the attribute");
    if (type == NC_CHAR) {
      std::string s(len, '\0');
      if (len > 0) check(nc_get_att_text(ncid_, varid, att, s.data()), field, "cannot read");
      while (!s.empty() && s.back() == '\0') s.pop_back();
      return s;
    }
    if (type == NC_STRING && len == 1) {
      char* p = nullptr;
      check(nc_get_att_string(ncid_, varid, att, &p), field, "cannot read");
      std::string s = p != nullptr ? p : "";
      nc_free_string(1, &p);
      return s;
    }
    fail(field, "must be a text attribute");
  }

  // A numeric attribute as doubles (missing_value may be a vector, CF §2.5.1);
  // empty if absent.
  std::vector<double> number_attribute(int varid, const char* att) const {
    const std::string field = var_name(varid) + ":" + att;
    nc_type type = NC_NAT;
    std::size_t len = 0;
    const int status = nc_inq_att(ncid_, varid, att, &type, &len);
    if (status == NC_ENOTATT) return {};
    check(status, field, "cannot read the attribute");
    if (!is_numeric_type(type) || len == 0) fail(field, "must be a numeric attribute");
    std::vector<double> v(len);
    check(nc_get_att_double(ncid_, varid, att, v.data()), field, "cannot read");
    return v;
  }

  std::vector<double> read_1d(int varid, std::size_t n) const {
    std::vector<double> v(n);
    if (n > 0)
      check(nc_get_var_double(ncid_, varid, v.data()), var_name(varid), "cannot read values");
    return v;
  }

  int ncid() const { return ncid_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  int ncid_;
};

struct AxisInfo {
  int dimid = -1;
  std::string name;  // dimension name
  std::size_t len = 0;
  int coord_var = -1;  // coordinate variable (same name, 1-D over the dimension)
};

// How one 4-D data variable maps onto the axes: position of each axis among
// the variable's dimensions, packing, fill values, units.
struct DataVar {
  int varid = -1;
  std::string name;
  std::array<int, 4> position{};     // position[axis] = index in the variable's dimensions
  double scale = 1.0, offset = 0.0;  // CF §8.1 packing: value = raw·scale + offset
  std::vector<double> missing;       // raw values that mean "no data"
  bool missing_nan = false;          // a NaN fill value: NaN is missing
};

// Identifies the four axes of the concentration variable's dimensions.
std::array<AxisInfo, 4> identify_axes(const NcReader& r, int varid, const std::vector<int>& dims) {
  const std::string var = r.var_name(varid);
  std::array<AxisInfo, 4> axes;
  std::array<bool, 4> seen{};
  for (int dimid : dims) {
    AxisInfo a;
    a.dimid = dimid;
    a.name = r.dim_name(dimid);
    a.len = r.dim_len(dimid);
    int cv = -1;
    if (nc_inq_varid(r.ncid(), a.name.c_str(), &cv) == NC_NOERR) {
      const std::vector<int> cd = r.var_dims(cv);
      if (cd.size() == 1 && cd[0] == dimid) a.coord_var = cv;
    }
    int axis = -1;
    if (a.coord_var >= 0) {
      if (const auto att = r.text_attribute(a.coord_var, "axis")) {
        const std::string v = lower(trim(*att));
        axis = v == "x" ? kX : v == "y" ? kY : v == "z" ? kZ : v == "t" ? kT : -2;
        if (axis == -2)
          r.fail(a.name + ":axis", fmt::format("axis '{}' is not X, Y, Z or T", *att));
      }
    }
    if (axis < 0) {
      for (int k = 0; k < 4; ++k)
        if (a.name == kAxisNames[k]) axis = k;
    }
    if (axis < 0)
      r.fail(var, fmt::format("dimension '{}' is not one of x, y, z, time, and has no coordinate "
                              "variable with an axis attribute X, Y, Z or T (geographic "
                              "latitude/longitude grids are not supported)",
                              a.name));
    if (seen[axis])
      r.fail(var, fmt::format("two dimensions ('{}' and '{}') are both the {} axis",
                              axes[axis].name, a.name, kAxisNames[axis]));
    seen[axis] = true;
    axes[axis] = a;
  }
  return axes;
}

// A 4-D data variable over exactly the axes' dimensions, in any order.
DataVar data_variable(const NcReader& r, const std::string& name,
                      const std::array<AxisInfo, 4>& axes) {
  DataVar d;
  d.varid = r.find_variable(name);
  d.name = name;
  const std::vector<int> dims = r.var_dims(d.varid);
  std::string dim_list;
  for (std::size_t i = 0; i < dims.size(); ++i) dim_list += (i ? ", " : "") + r.dim_name(dims[i]);
  if (dims.size() != 4)
    r.fail(name, fmt::format("has {} dimensions ({}); expected 4: (time, z, y, x)", dims.size(),
                             dim_list));
  if (!is_numeric_type(r.var_type(d.varid))) r.fail(name, "is not a numeric variable");
  for (int axis = 0; axis < 4; ++axis) {
    const auto it = std::find(dims.begin(), dims.end(), axes[axis].dimid);
    if (axes[axis].dimid < 0 || it == dims.end())
      r.fail(name,
             fmt::format("dimensions ({}) are not those of the concentration variable "
                         "({}, {}, {}, {} in any order)",
                         dim_list, axes[kT].name, axes[kZ].name, axes[kY].name, axes[kX].name));
    d.position[axis] = static_cast<int>(it - dims.begin());
  }
  if (const auto s = r.number_attribute(d.varid, "scale_factor"); !s.empty()) d.scale = s[0];
  if (const auto o = r.number_attribute(d.varid, "add_offset"); !o.empty()) d.offset = o[0];
  if (!std::isfinite(d.scale) || !std::isfinite(d.offset))
    r.fail(name + ":scale_factor", "scale_factor and add_offset must be finite");
  // CF §2.5.1: _FillValue and missing_value mark missing data. Without a
  // _FillValue attribute netCDF's default fill value for the type applies
  // (NUG, "Fill Values"); byte types have none by convention.
  std::vector<double> fill = r.number_attribute(d.varid, "_FillValue");
  if (fill.empty()) {
    int no_fill = 0;
    r.check(nc_inq_var_fill(r.ncid(), d.varid, &no_fill, nullptr), name, "cannot read fill mode");
    if (!no_fill) {
      switch (r.var_type(d.varid)) {
        case NC_FLOAT:
          fill = {NC_FILL_FLOAT};
          break;
        case NC_DOUBLE:
          fill = {NC_FILL_DOUBLE};
          break;
        case NC_SHORT:
          fill = {NC_FILL_SHORT};
          break;
        case NC_USHORT:
          fill = {NC_FILL_USHORT};
          break;
        case NC_INT:
          fill = {NC_FILL_INT};
          break;
        case NC_UINT:
          fill = {NC_FILL_UINT};
          break;
        case NC_INT64:
          fill = {static_cast<double>(NC_FILL_INT64)};
          break;
        case NC_UINT64:
          fill = {static_cast<double>(NC_FILL_UINT64)};
          break;
        default:
          break;
      }
    }
  }
  for (const auto& list : {fill, r.number_attribute(d.varid, "missing_value")})
    for (double m : list) {
      if (std::isnan(m))
        d.missing_nan = true;
      else
        d.missing.push_back(m);
    }
  return d;
}

struct Coordinates {
  double first = 0;             // coordinate of index 0, converted units
  double spacing = 0;           // signed, converted units
  double spacing_rounding = 0;  // how much the storage type's rounding may move `spacing`
  double min_centre = 0;        // smallest voxel-centre coordinate
  bool flipped = false;         // decreasing in the file
};

// Reads a spatial coordinate variable: metres or km, evenly spaced.
Coordinates spatial_coordinates(const NcReader& r, const AxisInfo& a) {
  if (a.coord_var < 0)
    r.fail(a.name, fmt::format("dimension '{}' has no coordinate variable (a 1-D variable of the "
                               "same name holding the voxel-centre positions)",
                               a.name));
  if (a.len < 2)
    r.fail(a.name, fmt::format("{} has {} point; at least 2 are needed to give the voxel size",
                               a.name, a.len));
  if (!is_numeric_type(r.var_type(a.coord_var))) r.fail(a.name, "is not numeric");
  const auto units = r.text_attribute(a.coord_var, "units");
  if (!units) r.fail(a.name + ":units", "missing; expected m or km");
  const auto factor = length_to_m(*units);
  if (!factor)
    r.fail(a.name + ":units", fmt::format("'{}' is not a length; expected m or km", *units));
  const std::vector<double> v = r.read_1d(a.coord_var, a.len);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      r.fail(fmt::format("{}[{}]", a.name, i), fmt::format("coordinate {} is not finite", v[i]));
  const std::size_t n = v.size();
  const double d = (v[n - 1] - v[0]) / static_cast<double>(n - 1);
  if (!(std::abs(d) > 0))
    r.fail(a.name, fmt::format("first and last coordinates are both {}", v[0]));
  const double tol =
      kUniformTolerance * std::abs(d) +
      storage_epsilon(r.var_type(a.coord_var)) * std::max(std::abs(v[0]), std::abs(v[n - 1]));
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double expected = v[0] + d * static_cast<double>(i);
    if (std::abs(v[i] - expected) > tol)
      r.fail(fmt::format("{}[{}]", a.name, i),
             fmt::format("{} is not evenly spaced: {}[{}] = {} {} but {}[0] = {} and {}[{}] = {} "
                         "put it at {} (tolerance {} relative to the spacing); obscura needs a "
                         "regular grid",
                         a.name, a.name, i, v[i], *units, a.name, v[0], a.name, n - 1, v[n - 1],
                         expected, kUniformTolerance));
  }
  Coordinates c;
  c.first = v[0] * *factor;
  c.spacing = d * *factor;
  c.flipped = d < 0;
  c.min_centre = std::min(v[0], v[n - 1]) * *factor;
  c.spacing_rounding = 2 * storage_epsilon(r.var_type(a.coord_var)) *
                       std::max(std::abs(v[0]), std::abs(v[n - 1])) / static_cast<double>(n - 1) *
                       *factor;
  return c;
}

std::vector<double> time_coordinates(const NcReader& r, const AxisInfo& a) {
  if (a.coord_var < 0)
    r.fail(a.name,
           fmt::format("dimension '{}' has no coordinate variable giving the times", a.name));
  if (a.len == 0) r.fail(a.name, "the file has no time steps");
  if (!is_numeric_type(r.var_type(a.coord_var))) r.fail(a.name, "is not numeric");
  const auto units = r.text_attribute(a.coord_var, "units");
  if (!units) r.fail(a.name + ":units", "missing; expected s, min, h or d (optionally 'since …')");
  const auto factor = time_to_s(*units);
  if (!factor)
    r.fail(a.name + ":units", fmt::format("'{}' is not a time unit; expected s, min, h or d "
                                          "(optionally 'since …')",
                                          *units));
  std::vector<double> t = r.read_1d(a.coord_var, a.len);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]))
      r.fail(fmt::format("{}[{}]", a.name, i), fmt::format("time {} is not finite", t[i]));
    if (i > 0 && !(t[i] > t[i - 1]))
      r.fail(fmt::format("{}[{}]", a.name, i),
             fmt::format("time {} is not after {}[{}] = {}: times must be strictly increasing",
                         t[i], a.name, i - 1, t[i - 1]));
  }
  for (double& x : t) x *= *factor;
  return t;
}

// Reads time step `step` of `var` into `out` (x fastest), applying packing and
// the unit conversion `value·factor + add`. Missing values become `missing_as`
// or, if that is empty, an error naming the voxel.
void read_frame(const NcReader& r, const DataVar& var, const std::array<AxisInfo, 4>& axes,
                const std::array<Coordinates, 3>& coords, std::size_t step, double factor,
                double add, std::optional<float> missing_as, std::vector<double>& staging,
                ScalarGrid& out, const char* quantity, const char* unit, bool strictly_positive) {
  std::array<std::size_t, 4> start{}, count{};
  for (int axis = 0; axis < 4; ++axis) {
    start[var.position[axis]] = axis == kT ? step : 0;
    count[var.position[axis]] = axis == kT ? 1 : axes[axis].len;
  }
  r.check(nc_get_vara_double(r.ncid(), var.varid, start.data(), count.data(), staging.data()),
          fmt::format("{}[{}={}]", var.name, axes[kT].name, step), "cannot read values");
  // The slab is in the variable's own dimension order (C order, last fastest).
  std::array<std::size_t, 4> stride{};
  std::size_t s = 1;
  for (int p = 3; p >= 0; --p) {
    stride[p] = s;
    s *= count[p];
  }
  const std::size_t sx = stride[var.position[kX]], sy = stride[var.position[kY]],
                    sz = stride[var.position[kZ]];
  const GridDims& d = out.dims;
  for (int k = 0; k < d.nz; ++k) {
    const std::size_t fk = coords[kZ].flipped ? d.nz - 1 - k : k;
    for (int j = 0; j < d.ny; ++j) {
      const std::size_t fj = coords[kY].flipped ? d.ny - 1 - j : j;
      for (int i = 0; i < d.nx; ++i) {
        const std::size_t fi = coords[kX].flipped ? d.nx - 1 - i : i;
        const double raw = staging[fi * sx + fj * sy + fk * sz];
        float& dst = out.values[out.index(i, j, k)];
        const bool missing =
            (var.missing_nan && std::isnan(raw)) ||
            std::find(var.missing.begin(), var.missing.end(), raw) != var.missing.end();
        const auto voxel = [&] {
          return fmt::format("{}[{}={}] voxel ({},{},{})", var.name, axes[kT].name, step, i, j, k);
        };
        if (missing) {
          if (!missing_as)
            r.fail(voxel(), fmt::format("missing value ({} is the variable's _FillValue or "
                                        "missing_value){}",
                                        raw,
                                        strictly_positive ? ""
                                                          : "; pass missing_concentration_as_zero "
                                                            "to read missing values as 0"));
          dst = *missing_as;
          continue;
        }
        const double v = (raw * var.scale + var.offset) * factor + add;
        dst = static_cast<float>(v);
        const bool bad = !std::isfinite(dst) || (strictly_positive ? !(dst > 0.0f) : dst < 0.0f);
        if (bad)
          r.fail(voxel(), fmt::format("{} {} {} must be finite and {} 0", quantity, v, unit,
                                      strictly_positive ? ">" : ">="));
      }
    }
  }
}

ConcentrationSeries read_locked(const std::filesystem::path& path, const NetcdfReadOptions& opt) {
  const std::string file = path.string();
  NcHandle handle;
  const int status = nc_open(path.c_str(), NC_NOWRITE, &handle.id);
  if (status != NC_NOERR) {
    handle.id = -1;
    throw InputError(file, "", fmt::format("not a readable netCDF file: {}", nc_strerror(status)));
  }
  const NcReader r(file, handle.id);

  const int conc_id = r.find_variable(opt.concentration);
  const std::vector<int> dims = r.var_dims(conc_id);
  if (dims.size() != 4) {
    std::string list;
    for (std::size_t i = 0; i < dims.size(); ++i) list += (i ? ", " : "") + r.dim_name(dims[i]);
    r.fail(opt.concentration,
           fmt::format("has {} dimensions ({}); expected 4: (time, z, y, x)", dims.size(), list));
  }
  const std::array<AxisInfo, 4> axes = identify_axes(r, conc_id, dims);

  // Sizes before any allocation: every frame's grids plus one staging slab.
  for (int a = 0; a < 3; ++a)
    if (axes[a].len > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      r.fail(axes[a].name, fmt::format("length {} is too large", axes[a].len));
  const std::uint64_t channels = opt.temperature.empty() ? 1 : 2;
  std::uint64_t voxels = 0, grid_bytes = 0, total = 0;
  const bool overflow =
      __builtin_mul_overflow(static_cast<std::uint64_t>(axes[kX].len),
                             static_cast<std::uint64_t>(axes[kY].len), &voxels) ||
      __builtin_mul_overflow(voxels, static_cast<std::uint64_t>(axes[kZ].len), &voxels) ||
      __builtin_mul_overflow(voxels, static_cast<std::uint64_t>(axes[kT].len) * channels * 4,
                             &grid_bytes) ||
      __builtin_add_overflow(grid_bytes, voxels * 8, &total);
  const std::uint64_t available = available_memory_bytes();
  if (overflow || total > available)
    r.fail(
        opt.concentration,
        fmt::format("{} time steps of {} x {} x {} voxels ({} {}) need {:.3g} GiB but only "
                    "{:.3g} GiB of memory is available",
                    axes[kT].len, axes[kX].len, axes[kY].len, axes[kZ].len, channels,
                    channels == 1 ? "variable" : "variables",
                    static_cast<double>(axes[kX].len) * static_cast<double>(axes[kY].len) *
                        static_cast<double>(axes[kZ].len) *
                        (4.0 * static_cast<double>(channels * axes[kT].len) + 8.0) / 1073741824.0,
                    available / 1073741824.0));

  std::array<Coordinates, 3> coords;
  for (int a = 0; a < 3; ++a) coords[a] = spatial_coordinates(r, axes[a]);
  const std::vector<double> times = time_coordinates(r, axes[kT]);
  // Cubic voxels (ScalarGrid has one voxel size).
  const double h = std::abs(coords[kX].spacing);
  for (int a = 1; a < 3; ++a)
    if (std::abs(std::abs(coords[a].spacing) - h) >
        kUniformTolerance * h + coords[a].spacing_rounding + coords[kX].spacing_rounding)
      r.fail(axes[a].name,
             fmt::format("spacing {} m differs from {}'s {} m: obscura grids have "
                         "cubic voxels, so x, y and z must be equally spaced (to a "
                         "relative {}); resample the data onto an isotropic grid",
                         std::abs(coords[a].spacing), axes[kX].name, h, kUniformTolerance));
  GridPlacement placement;
  placement.voxel_size_m = h;
  placement.origin_m = {coords[kX].min_centre - 0.5 * h, coords[kY].min_centre - 0.5 * h,
                        coords[kZ].min_centre - 0.5 * h};
  const GridDims gd{static_cast<int>(axes[kX].len), static_cast<int>(axes[kY].len),
                    static_cast<int>(axes[kZ].len)};

  DataVar conc = data_variable(r, opt.concentration, axes);
  std::optional<std::string> cu = r.text_attribute(conc.varid, "units");
  if (!cu && !opt.concentration_units_if_missing.empty()) cu = opt.concentration_units_if_missing;
  if (!cu)
    r.fail(opt.concentration + ":units",
           "missing; expected a mass concentration such as g m-3, kg m-3 or mg m-3");
  const auto conc_factor = concentration_to_g_m3(*cu);
  if (!conc_factor)
    r.fail(opt.concentration + ":units",
           fmt::format("'{}' is not a mass concentration; expected g m-3, kg m-3, mg m-3 or ug m-3",
                       *cu));

  std::optional<DataVar> temp;
  double temp_offset = 0;
  if (!opt.temperature.empty()) {
    temp = data_variable(r, opt.temperature, axes);
    const auto tu = r.text_attribute(temp->varid, "units");
    if (!tu) r.fail(opt.temperature + ":units", "missing; expected K or degC");
    const auto off = temperature_offset_to_k(*tu);
    if (!off)
      r.fail(opt.temperature + ":units",
             fmt::format("'{}' is not a temperature unit; expected K or degC", *tu));
    temp_offset = *off;
  }

  ConcentrationSeries series;
  series.source = file;
  series.frames.reserve(times.size());
  std::vector<double> staging(static_cast<std::size_t>(voxels));
  const std::optional<float> conc_missing =
      opt.missing_concentration_as_zero ? std::optional<float>(0.0f) : std::nullopt;
  for (std::size_t t = 0; t < times.size(); ++t) {
    ConcentrationFrame frame;
    frame.time_s = times[t];
    ScalarGrid& c = frame.concentration_g_m3;
    c.dims = gd;
    c.placement = placement;
    c.values.resize(static_cast<std::size_t>(voxels));
    read_frame(r, conc, axes, coords, t, *conc_factor, 0.0, conc_missing, staging, c,
               "concentration", "g/m³", false);
    if (temp) {
      ScalarGrid g;
      g.dims = gd;
      g.placement = placement;
      g.values.resize(static_cast<std::size_t>(voxels));
      read_frame(r, *temp, axes, coords, t, 1.0, temp_offset, std::nullopt, staging, g,
                 "temperature", "K", true);
      frame.temperature_k = std::move(g);
    }
    series.frames.push_back(std::move(frame));
  }
  return series;
}

// ---------------------------------------------------------------------------
// Writer.

void check_series(const std::string& file, const ConcentrationSeries& s) {
  if (s.frames.empty()) throw InputError(file, "frames", "nothing to write: no frames");
  const ScalarGrid& g0 = s.frames.front().concentration_g_m3;
  const bool with_t = s.frames.front().temperature_k.has_value();
  for (std::size_t f = 0; f < s.frames.size(); ++f) {
    const ConcentrationFrame& fr = s.frames[f];
    const std::string field = fmt::format("frames[{}]", f);
    if (!std::isfinite(fr.time_s))
      throw InputError(file, field, fmt::format("time {} s is not finite", fr.time_s));
    if (f > 0 && !(fr.time_s > s.frames[f - 1].time_s))
      throw InputError(file, field,
                       fmt::format("time {} s is not after the previous frame's {} s", fr.time_s,
                                   s.frames[f - 1].time_s));
    if (fr.temperature_k.has_value() != with_t)
      throw InputError(file, field, "temperature must be present in every frame or in none");
    std::vector<const ScalarGrid*> grids{&fr.concentration_g_m3};
    if (fr.temperature_k) grids.push_back(&*fr.temperature_k);
    for (const ScalarGrid* g : grids) {
      const char* what = g == &fr.concentration_g_m3 ? "concentration" : "temperature";
      if (g->dims.nx < 2 || g->dims.ny < 2 || g->dims.nz < 2)
        throw InputError(file, field,
                         fmt::format("{} dims {}x{}x{}: at least 2 voxels per axis are needed "
                                     "so that the coordinates give the voxel size",
                                     what, g->dims.nx, g->dims.ny, g->dims.nz));
      if (g->values.size() != g->dims.count())
        throw InputError(file, field,
                         fmt::format("{} has {} values for {}x{}x{} voxels", what, g->values.size(),
                                     g->dims.nx, g->dims.ny, g->dims.nz));
      if (!(std::isfinite(g->placement.voxel_size_m) && g->placement.voxel_size_m > 0.0) ||
          !is_finite(g->placement.origin_m))
        throw InputError(file, field,
                         fmt::format("{}: voxel size must be finite and > 0, origin "
                                     "finite",
                                     what));
      if (!(g->placement.rotation == Mat3::identity()))
        throw InputError(file, field,
                         fmt::format("{}: a rotated grid cannot be written with x, y, "
                                     "z coordinate variables",
                                     what));
      if (!(g->dims == g0.dims) || !(g->placement.origin_m == g0.placement.origin_m) ||
          g->placement.voxel_size_m != g0.placement.voxel_size_m)
        throw InputError(file, field,
                         fmt::format("{} grid differs from frame 0's: a file has one grid", what));
    }
  }
}

class NcWriter {
 public:
  NcWriter(std::string file, int ncid) : file_(std::move(file)), ncid_(ncid) {}
  void check(int status, std::string_view doing) const {
    if (status != NC_NOERR)
      throw Error(fmt::format("cannot write {}: {}: {}", file_, doing, nc_strerror(status)));
  }
  void text(int varid, const char* name, const std::string& value) const {
    check(nc_put_att_text(ncid_, varid, name, value.size(), value.c_str()), name);
  }
  int ncid() const { return ncid_; }

 private:
  std::string file_;
  int ncid_;
};

void write_locked(const std::filesystem::path& path, const ConcentrationSeries& s) {
  const std::string file = path.string();
  const ScalarGrid& g0 = s.frames.front().concentration_g_m3;
  const bool with_t = s.frames.front().temperature_k.has_value();
  const GridDims d = g0.dims;
  const GridPlacement& p = g0.placement;

  AtomicFile atomic(path);
  NcHandle h;
  {
    const int status = nc_create(atomic.temp_path().c_str(), NC_NETCDF4 | NC_CLOBBER, &h.id);
    if (status != NC_NOERR) {
      h.id = -1;
      throw Error(
          fmt::format("cannot create {}: {}", atomic.temp_path().string(), nc_strerror(status)));
    }
  }
  const NcWriter w(file, h.id);
  const int nc = h.id;
  int dim_t = 0, dim_z = 0, dim_y = 0, dim_x = 0;
  w.check(nc_def_dim(nc, "time", NC_UNLIMITED, &dim_t), "time dimension");
  w.check(nc_def_dim(nc, "z", static_cast<std::size_t>(d.nz), &dim_z), "z dimension");
  w.check(nc_def_dim(nc, "y", static_cast<std::size_t>(d.ny), &dim_y), "y dimension");
  w.check(nc_def_dim(nc, "x", static_cast<std::size_t>(d.nx), &dim_x), "x dimension");

  int var_t = 0, var_z = 0, var_y = 0, var_x = 0;
  w.check(nc_def_var(nc, "time", NC_DOUBLE, 1, &dim_t, &var_t), "time variable");
  w.check(nc_def_var(nc, "z", NC_DOUBLE, 1, &dim_z, &var_z), "z variable");
  w.check(nc_def_var(nc, "y", NC_DOUBLE, 1, &dim_y, &var_y), "y variable");
  w.check(nc_def_var(nc, "x", NC_DOUBLE, 1, &dim_x, &var_x), "x variable");
  w.text(var_t, "standard_name", "time");
  w.text(var_t, "long_name", "time");
  w.text(var_t, "units", "s");
  w.text(var_t, "axis", "T");
  const struct {
    int var;
    const char* axis;
    const char* long_name;
  } spatial[] = {{var_x, "X", "x (east), voxel centre"},
                 {var_y, "Y", "y (north), voxel centre"},
                 {var_z, "Z", "z (up), voxel centre"}};
  for (const auto& sp : spatial) {
    w.text(sp.var, "long_name", sp.long_name);
    w.text(sp.var, "units", "m");
    w.text(sp.var, "axis", sp.axis);
  }
  w.text(var_z, "positive", "up");  // CF §4.3: required for a height-like axis

  // One time step per chunk (what the reader reads at once), at most ~16 MiB.
  const std::size_t plane = static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny) * 4;
  const std::size_t target = std::size_t{16} << 20;
  std::array<std::size_t, 4> chunk{1, 1, static_cast<std::size_t>(d.ny),
                                   static_cast<std::size_t>(d.nx)};
  if (plane <= target)
    chunk[1] = std::clamp<std::size_t>(target / plane, 1, static_cast<std::size_t>(d.nz));
  else
    chunk[2] = std::clamp<std::size_t>(target / (static_cast<std::size_t>(d.nx) * 4), 1,
                                       static_cast<std::size_t>(d.ny));
  const std::array<int, 4> data_dims{dim_t, dim_z, dim_y, dim_x};
  const auto def_data = [&](const char* name, const char* units, const char* long_name,
                            const char* standard_name) {
    int v = 0;
    w.check(nc_def_var(nc, name, NC_FLOAT, 4, data_dims.data(), &v), name);
    w.check(nc_def_var_chunking(nc, v, NC_CHUNKED, chunk.data()), name);
    w.check(nc_def_var_deflate(nc, v, 1, 1, 4), name);
    w.text(v, "units", units);
    w.text(v, "long_name", long_name);
    if (standard_name != nullptr) w.text(v, "standard_name", standard_name);
    return v;
  };
  const int var_c = def_data("concentration", "g m-3", "obscurant mass concentration", nullptr);
  const int var_temp = with_t ? def_data("temperature", "K", "temperature", "air_temperature") : -1;
  w.text(NC_GLOBAL, "Conventions", "CF-1.8");
  w.text(NC_GLOBAL, "title", "obscurant concentration time series");
  w.text(NC_GLOBAL, "source", s.source.empty() ? std::string("obscura") : s.source);
  w.text(NC_GLOBAL, "history", "written by obscura");
  w.check(nc_enddef(nc), "end of definitions");

  // Voxel centres: origin + h·(i + ½) (docs/formats.md, "Grid placement").
  const auto centres = [&](int n, double origin) {
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) c[i] = origin + p.voxel_size_m * (i + 0.5);
    return c;
  };
  w.check(nc_put_var_double(nc, var_x, centres(d.nx, p.origin_m.x).data()), "x values");
  w.check(nc_put_var_double(nc, var_y, centres(d.ny, p.origin_m.y).data()), "y values");
  w.check(nc_put_var_double(nc, var_z, centres(d.nz, p.origin_m.z).data()), "z values");
  for (std::size_t f = 0; f < s.frames.size(); ++f) {
    const ConcentrationFrame& fr = s.frames[f];
    const std::size_t one = 1;
    w.check(nc_put_vara_double(nc, var_t, &f, &one, &fr.time_s), "time values");
    // ScalarGrid values are x fastest: exactly C order over (z, y, x).
    const std::array<std::size_t, 4> start{f, 0, 0, 0};
    const std::array<std::size_t, 4> count{1, static_cast<std::size_t>(d.nz),
                                           static_cast<std::size_t>(d.ny),
                                           static_cast<std::size_t>(d.nx)};
    w.check(nc_put_vara_float(nc, var_c, start.data(), count.data(),
                              fr.concentration_g_m3.values.data()),
            "concentration values");
    if (with_t)
      w.check(nc_put_vara_float(nc, var_temp, start.data(), count.data(),
                                fr.temperature_k->values.data()),
              "temperature values");
  }
  w.check(nc_close(h.release()), "close");
  atomic.commit();
}

}  // namespace

ConcentrationSeries read_netcdf_cf(const std::filesystem::path& path,
                                   const NetcdfReadOptions& options) {
  const std::string file = path.string();
  if (options.concentration.empty())
    throw InputError(file, "concentration", "the concentration variable name is empty");
  if (options.temperature == options.concentration)
    throw InputError(file, "temperature", "the temperature variable is the concentration's");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "", "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "", "not a regular file");
  std::lock_guard lock(netcdf_mutex());
  return read_locked(path, options);
}

void write_netcdf_cf(const std::filesystem::path& path, const ConcentrationSeries& series) {
  check_series(path.string(), series);
  std::lock_guard lock(netcdf_mutex());
  write_locked(path, series);
}

}  // namespace obscura
