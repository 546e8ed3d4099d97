#pragma once
// CFD concentration time series from NetCDF files that follow the CF
// conventions (CF-1.x, "NetCDF Climate and Forecast Metadata Conventions"),
// and a writer for the same layout. The exact rules are in docs/formats.md,
// "CFD concentration import"; in short:
//  * a 4-D variable (default name "concentration") over dimensions whose
//    coordinate variables are x, y, z (metres) and time (seconds), in any
//    order — CF recommends (time, z, y, x), which the writer uses;
//  * an axis is recognised by its coordinate variable's `axis` attribute
//    (X, Y, Z, T) or, failing that, by the dimension name x, y, z or time;
//  * coordinates are voxel centres, evenly spaced, the same spacing along x, y
//    and z (cubic voxels), to 1e−6 relative; a decreasing axis is flipped;
//  * units are converted: m or km; s, min, h, d (with or without "since …");
//    g m-3, kg m-3, mg m-3, ug m-3 for the concentration; K or degC;
//  * CF packing (scale_factor, add_offset) is applied; _FillValue or
//    missing_value (or netCDF's default fill value) marks a missing value,
//    which is an error unless the caller asks for missing values to be 0.
#include <filesystem>
#include <string>

#include "obscura/medium/concentration_series.h"

namespace obscura {

struct NetcdfReadOptions {
  // Name of the 4-D concentration variable.
  std::string concentration = "concentration";
  // Name of an optional 4-D temperature variable (K or degC) over the same
  // dimensions; empty: the frames have no temperature.
  std::string temperature;
  // Units assumed when the concentration variable has no `units` attribute
  // (e.g. "g m-3"); empty: a missing `units` is an error.
  std::string concentration_units_if_missing;
  // Missing values (_FillValue, missing_value) in the concentration: false →
  // error naming the first one; true → read as 0 g/m³ (e.g. solid cells of a
  // CFD mesh). Missing temperatures are always an error.
  bool missing_concentration_as_zero = false;
};

// Reads every time step of the file. Sizes are checked against the memory
// available before anything is allocated. Values must be finite, the
// concentration ≥ 0 g/m³ and the temperature > 0 K. Throws InputError naming
// the file and the variable or attribute ("concentration:units"), the
// coordinate index, or the voxel and time index.
ConcentrationSeries read_netcdf_cf(const std::filesystem::path& path,
                                   const NetcdfReadOptions& options = {});

// Writes `series` as a CF-1.8 netCDF-4 file: dimensions time (unlimited), z,
// y, x; coordinate variables (double, "m", "s") at the voxel centres;
// concentration(time, z, y, x) float "g m-3" and, when the frames have one,
// temperature(time, z, y, x) float "K"; zlib-compressed one time step per
// chunk. Every frame must share one grid (dims and placement, identity
// rotation, at least 2 voxels along each axis so the reader can recover the
// spacing), times strictly increasing, temperature in all frames or none.
// Values are written as given. Atomic: written under a temporary name and
// renamed when complete. Throws InputError for a bad series, Error on I/O
// failure.
void write_netcdf_cf(const std::filesystem::path& path, const ConcentrationSeries& series);

}  // namespace obscura
