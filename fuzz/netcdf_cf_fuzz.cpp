// A NetCDF-CF concentration file (classic or netCDF-4/HDF5), read as prepare
// reads CFD output: concentration alone, then with a temperature variable.
#include "harness.h"
#include "obscura/io/netcdf_cf.h"

OBSCURA_FUZZ_HARNESS(netcdf_cf) {
  const auto path = obscura::fuzz::scratch_file("input.nc", bytes);
  obscura::fuzz::ignore_input_errors([&] { obscura::read_netcdf_cf(path); });
  obscura::NetcdfReadOptions with_temperature;
  with_temperature.temperature = "temperature";
  with_temperature.missing_concentration_as_zero = true;
  obscura::read_netcdf_cf(path, with_temperature);
}
