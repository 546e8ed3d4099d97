#pragma once
// A walk over a netCDF classic-format header (CDF-1, CDF-2 and CDF-5: the
// "netCDF Classic and 64-bit Offset Format" and "CDF-5" specifications of
// Unidata) that checks every count and length against the file's size before
// netCDF-C reads it. nc_open allocates what the header says: a mutated name
// length made new_NC_string calloc 3.1 GB before any check. The walk also
// refuses a variable whose data would end past the end of the file, which
// netCDF-C would read as zeros. Files in the netCDF-4 (HDF5) format are left
// to HDF5. Internal to io/.
#include <filesystem>

namespace obscura::netcdf_cf {

// Throws InputError naming the file and the part of the header (a dimension,
// an attribute, a variable) that does not fit; does nothing for a file that
// is not in a classic format.
void check_netcdf_classic_header(const std::filesystem::path& path);

}  // namespace obscura::netcdf_cf
