// NetCDF-CF concentration files, read as prepare reads CFD output:
// concentration alone, then with a temperature variable. Two harnesses, by
// the library that parses the file's structure:
//   netcdf_cf   classic files (CDF-1, CDF-2, CDF-5), parsed by netCDF-C itself
//               after obscura's own header walk (io/netcdf_classic_check.h);
//   netcdf4_cf  netCDF-4 files, whose structure HDF5 parses.
// HDF5 1.10.8 (Debian 12) is not robust to corrupt files: fuzzing netcdf4_cf
// finds memory errors and hangs inside HDF5's global heap within seconds
// (docs/reliability.md, "Known upstream defects"). So CI fuzzes netcdf_cf and
// only replays netcdf4_cf's seeds and regressions; netcdf_cf leaves any input
// that netCDF-C would hand to HDF5 to netcdf4_cf.
#include <filesystem>

#include "harness.h"
#include "obscura/io/netcdf_cf.h"
#include "obscura/io/netcdf_child_read.h"

namespace {

void read_twice(const std::filesystem::path& path) {
  obscura::fuzz::ignore_input_errors([&] { obscura::read_netcdf_cf(path); });
  obscura::NetcdfReadOptions with_temperature;
  with_temperature.temperature = "temperature";
  with_temperature.missing_concentration_as_zero = true;
  obscura::read_netcdf_cf(path, with_temperature);
}

}  // namespace

OBSCURA_FUZZ_HARNESS(netcdf_cf) {
  const auto path = obscura::fuzz::scratch_file("input.nc", bytes);
  // The reader's own test of what netCDF-C would hand to HDF5.
  if (obscura::netcdf_cf::is_hdf5_container(path)) return;  // netcdf4_cf's input
  read_twice(path);
}

OBSCURA_FUZZ_HARNESS(netcdf4_cf) { read_twice(obscura::fuzz::scratch_file("input.nc", bytes)); }
