#include "obscura/io/netcdf_file.h"

#include <fmt/format.h>

#include <cfloat>

#include "obscura/core/error.h"

namespace obscura::netcdf_cf {

std::mutex& netcdf_mutex() {
  static std::mutex m;
  return m;
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

double storage_epsilon(nc_type t) {
  if (t == NC_FLOAT) return FLT_EPSILON;
  if (t == NC_DOUBLE) return 4 * DBL_EPSILON;
  return 0.0;
}

void NcReader::fail(const std::string& field, const std::string& what) const {
  throw InputError(file_, field, what);
}

void NcReader::check(int status, const std::string& field, std::string_view doing) const {
  if (status != NC_NOERR) fail(field, fmt::format("{}: {}", doing, nc_strerror(status)));
}

std::string NcReader::var_name(int varid) const {
  char name[NC_MAX_NAME + 1] = {};
  check(nc_inq_varname(ncid_, varid, name), "", "cannot read a variable name");
  return name;
}

std::string NcReader::dim_name(int dimid) const {
  char name[NC_MAX_NAME + 1] = {};
  check(nc_inq_dimname(ncid_, dimid, name), "", "cannot read a dimension name");
  return name;
}

std::size_t NcReader::dim_len(int dimid) const {
  std::size_t len = 0;
  check(nc_inq_dimlen(ncid_, dimid, &len), dim_name(dimid), "cannot read the dimension length");
  return len;
}

std::string NcReader::variable_list() const {
  int n = 0;
  check(nc_inq_nvars(ncid_, &n), "", "cannot list variables");
  if (n == 0) return "the file has no variables";
  std::string s = "variables in the file: ";
  for (int v = 0; v < n; ++v) s += (v ? ", " : "") + var_name(v);
  return s;
}

int NcReader::find_variable(const std::string& name) const {
  int varid = -1;
  const int status = nc_inq_varid(ncid_, name.c_str(), &varid);
  if (status == NC_ENOTVAR)
    fail(name, fmt::format("no variable named '{}'; {}", name, variable_list()));
  check(status, name, "cannot look up the variable");
  return varid;
}

std::vector<int> NcReader::var_dims(int varid) const {
  int ndims = 0;
  check(nc_inq_varndims(ncid_, varid, &ndims), var_name(varid), "cannot read the dimensions");
  std::vector<int> dims(static_cast<std::size_t>(ndims));
  check(nc_inq_vardimid(ncid_, varid, dims.data()), var_name(varid), "cannot read the dimensions");
  return dims;
}

nc_type NcReader::var_type(int varid) const {
  nc_type t = NC_NAT;
  check(nc_inq_vartype(ncid_, varid, &t), var_name(varid), "cannot read the type");
  return t;
}

std::optional<std::string> NcReader::text_attribute(int varid, const char* att) const {
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

std::vector<double> NcReader::number_attribute(int varid, const char* att) const {
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

std::vector<double> NcReader::read_1d(int varid, std::size_t n) const {
  std::vector<double> v(n);
  if (n > 0)
    check(nc_get_var_double(ncid_, varid, v.data()), var_name(varid), "cannot read values");
  return v;
}

}  // namespace obscura::netcdf_cf
