#pragma once
// The axes of a CF concentration variable (io/netcdf_cf.h): which dimension
// is x, y, z and time (by the coordinate variable's `axis` attribute, else by
// the dimension's name), and the coordinate values along each, checked to be
// finite, in known units and, in space, evenly spaced. Internal to io/.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "obscura/io/netcdf_file.h"

namespace obscura::netcdf_cf {

// Coordinates are "evenly spaced" and "isotropic" to this relative tolerance.
inline constexpr double kUniformTolerance = 1e-6;

enum Axis { kX = 0, kY = 1, kZ = 2, kT = 3 };
inline constexpr const char* kAxisNames[] = {"x", "y", "z", "time"};

struct AxisInfo {
  int dimid = -1;
  std::string name;  // dimension name
  std::size_t len = 0;
  int coord_var = -1;  // coordinate variable (same name, 1-D over the dimension)
};

// The axes of variable `varid`, whose dimensions are `dims` (four of them),
// indexed by Axis.
std::array<AxisInfo, 4> identify_axes(const NcReader& r, int varid, const std::vector<int>& dims);

struct Coordinates {
  double first = 0;             // coordinate of index 0, converted units
  double spacing = 0;           // signed, converted units
  double spacing_rounding = 0;  // how much the storage type's rounding may move `spacing`
  double min_centre = 0;        // smallest voxel-centre coordinate
  bool flipped = false;         // decreasing in the file
};

// Reads a spatial coordinate variable: metres or km, evenly spaced.
Coordinates spatial_coordinates(const NcReader& r, const AxisInfo& a);

// Reads the time coordinate: strictly increasing, converted to seconds.
std::vector<double> time_coordinates(const NcReader& r, const AxisInfo& a);

}  // namespace obscura::netcdf_cf
