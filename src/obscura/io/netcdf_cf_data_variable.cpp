#include "obscura/io/netcdf_cf_data_variable.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace obscura::netcdf_cf {
namespace {

// netCDF's default fill value for a variable of type t without _FillValue
// (NUG, "Fill Values"); none for byte types, by convention.
std::vector<double> default_fill_value(nc_type t) {
  switch (t) {
    case NC_FLOAT:
      return {NC_FILL_FLOAT};
    case NC_DOUBLE:
      return {NC_FILL_DOUBLE};
    case NC_SHORT:
      return {NC_FILL_SHORT};
    case NC_USHORT:
      return {NC_FILL_USHORT};
    case NC_INT:
      return {NC_FILL_INT};
    case NC_UINT:
      return {NC_FILL_UINT};
    case NC_INT64:
      return {static_cast<double>(NC_FILL_INT64)};
    case NC_UINT64:
      return {static_cast<double>(NC_FILL_UINT64)};
    default:
      return {};
  }
}

}  // namespace

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
    if (!no_fill) fill = default_fill_value(r.var_type(d.varid));
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

}  // namespace obscura::netcdf_cf
