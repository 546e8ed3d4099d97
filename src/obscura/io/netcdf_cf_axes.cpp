#include "obscura/io/netcdf_cf_axes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "obscura/io/netcdf_cf_units.h"

namespace obscura::netcdf_cf {

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

}  // namespace obscura::netcdf_cf
