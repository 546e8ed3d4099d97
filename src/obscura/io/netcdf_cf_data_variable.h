#pragma once
// A 4-D data variable of a CF file (io/netcdf_cf.h): where each axis lies
// among its dimensions, its packing (CF §8.1) and missing values (CF §2.5.1),
// and the reading of one time step into a grid. Internal to io/.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "obscura/io/netcdf_cf_axes.h"
#include "obscura/io/netcdf_file.h"
#include "obscura/medium/concentration_series.h"

namespace obscura::netcdf_cf {

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

// The 4-D data variable `name` over exactly the axes' dimensions, in any order.
DataVar data_variable(const NcReader& r, const std::string& name,
                      const std::array<AxisInfo, 4>& axes);

// Reads time step `step` of `var` into `out` (x fastest), applying packing and
// the unit conversion `value·factor + add`. Missing values become `missing_as`
// or, if that is empty, an error naming the voxel. Every value must be finite
// and > 0 (`strictly_positive`) or ≥ 0; `quantity` and `unit` name it in the
// error. `staging` holds one time step of raw values.
void read_frame(const NcReader& r, const DataVar& var, const std::array<AxisInfo, 4>& axes,
                const std::array<Coordinates, 3>& coords, std::size_t step, double factor,
                double add, std::optional<float> missing_as, std::vector<double>& staging,
                ScalarGrid& out, const char* quantity, const char* unit, bool strictly_positive);

}  // namespace obscura::netcdf_cf
