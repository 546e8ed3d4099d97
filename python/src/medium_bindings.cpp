// The medium layer in Python: obscura.VoxelGrid, a dense cloud keyframe built
// from numpy arrays (docs/formats.md, "Grid placement"). Arrays are indexed
// [i, j, k] (x, y, z), the spectral axis last: sigma_a, sigma_s and g have
// shape (nx, ny, nz, n_wavelengths), temperature (nx, ny, nz). Shapes and
// dtypes are checked here, with the argument named; values by the library
// (VoxelGrid::validate), which names the channel and voxel.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "obscura/core/error.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::python {
namespace {

constexpr const char* kSource = "VoxelGrid";

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    s += (d ? ", " : "") + std::to_string(a.shape(d)) + (a.ndim() == 1 ? "," : "");
  return s + ")";
}

// `value` as a float64 array of `ndim` dimensions; a non-floating dtype or
// another rank is an InputError naming `name` and what was expected.
py::array_t<double> floating_array(const py::object& value, const std::string& name, int ndim,
                                   const std::string& expected_shape) {
  const py::array a = py::array::ensure(value);
  if (!a) throw InputError(kSource, name, "must be a numpy array (or convertible to one)");
  const char kind = a.dtype().kind();
  if (kind != 'f')
    throw InputError(kSource, name,
                     "has dtype " + py::str(a.dtype()).cast<std::string>() +
                         ", expected a floating-point array (float32 or float64)");
  if (a.ndim() != ndim)
    throw InputError(kSource, name, "has shape " + shape_text(a) + ", expected " + expected_shape);
  return py::array_t<double, py::array::forcecast>::ensure(a);
}

void require_shape(const py::array& a, const std::string& name,
                   const std::vector<py::ssize_t>& shape, const std::string& expected) {
  for (std::size_t d = 0; d < shape.size(); ++d)
    if (a.shape(static_cast<py::ssize_t>(d)) != shape[d])
      throw InputError(kSource, name, "has shape " + shape_text(a) + ", expected " + expected);
}

std::shared_ptr<VoxelGrid> make_grid(const py::object& sigma_a_in, const py::object& sigma_s_in,
                                     const py::object& g_in, const py::object& temperature_in,
                                     std::vector<double> wavelengths_um,
                                     const std::array<double, 3>& origin, double voxel_size_m) {
  const std::string spectral = "(nx, ny, nz, n_wavelengths)";
  const auto sigma_a = floating_array(sigma_a_in, "sigma_a", 4, spectral);
  const auto sigma_s = floating_array(sigma_s_in, "sigma_s", 4, spectral);
  const auto g = floating_array(g_in, "g", 4, spectral);
  const auto temperature = floating_array(temperature_in, "temperature", 3, "(nx, ny, nz)");
  const std::vector<py::ssize_t> shape = {sigma_a.shape(0), sigma_a.shape(1), sigma_a.shape(2),
                                          static_cast<py::ssize_t>(wavelengths_um.size())};
  const std::string expected = "(" + std::to_string(shape[0]) + ", " + std::to_string(shape[1]) +
                               ", " + std::to_string(shape[2]) + ", " + std::to_string(shape[3]) +
                               ") (nx, ny, nz, len(wavelengths_um))";
  require_shape(sigma_a, "sigma_a", shape, expected);
  require_shape(sigma_s, "sigma_s", shape, expected);
  require_shape(g, "g", shape, expected);
  require_shape(temperature, "temperature", {shape[0], shape[1], shape[2]},
                "(" + std::to_string(shape[0]) + ", " + std::to_string(shape[1]) + ", " +
                    std::to_string(shape[2]) + ") (nx, ny, nz, as sigma_a)");
  if (!(std::isfinite(voxel_size_m) && voxel_size_m > 0))
    throw InputError(kSource, "voxel_size_m", "must be a finite length > 0 (m)");
  for (double o : origin)
    if (!std::isfinite(o)) throw InputError(kSource, "origin", "must be 3 finite coordinates (m)");
  for (std::size_t w = 0; w < wavelengths_um.size(); ++w)
    if (!(std::isfinite(wavelengths_um[w]) && wavelengths_um[w] > 0) ||
        (w > 0 && !(wavelengths_um[w] > wavelengths_um[w - 1])))
      throw InputError(kSource, "wavelengths_um",
                       "must be finite, > 0 and strictly increasing (um)");

  GridPlacement placement;
  placement.origin_m = Vec3(origin[0], origin[1], origin[2]);
  placement.voxel_size_m = voxel_size_m;
  const GridDims dims{static_cast<int>(shape[0]), static_cast<int>(shape[1]),
                      static_cast<int>(shape[2])};
  auto grid = std::make_shared<VoxelGrid>(dims, placement, std::move(wavelengths_um), kSource);
  const auto a = sigma_a.unchecked<4>(), s = sigma_s.unchecked<4>(), gg = g.unchecked<4>();
  const auto t = temperature.unchecked<3>();
  for (int k = 0; k < dims.nz; ++k)
    for (int j = 0; j < dims.ny; ++j)
      for (int i = 0; i < dims.nx; ++i) {
        const std::size_t v = grid->index(i, j, k);
        for (int w = 0; w < grid->spectral_count(); ++w) {
          grid->sigma_a(w)[v] = static_cast<float>(a(i, j, k, w));
          grid->sigma_s(w)[v] = static_cast<float>(s(i, j, k, w));
          grid->g(w)[v] = static_cast<float>(gg(i, j, k, w));
        }
        grid->temperature()[v] = static_cast<float>(t(i, j, k));
      }
  grid->validate(kSource);
  return grid;
}

}  // namespace

void bind_medium(py::module_& m) {
  py::class_<VoxelGrid, std::shared_ptr<VoxelGrid>>(
      m, "VoxelGrid",
      "A dense cloud keyframe: sigma_a, sigma_s (1/m) and g per voxel and wavelength, "
      "temperature (K) per voxel.")
      .def(py::init(&make_grid), py::kw_only(), py::arg("sigma_a"), py::arg("sigma_s"),
           py::arg("g"), py::arg("temperature"), py::arg("wavelengths_um"), py::arg("origin"),
           py::arg("voxel_size_m"),
           "Arrays indexed [i, j, k] (x, y, z): sigma_a, sigma_s, g of shape (nx, ny, nz, "
           "n_wavelengths), temperature (nx, ny, nz); origin: the grid's minimum corner (m).")
      .def_property_readonly(
          "shape",
          [](const VoxelGrid& g) { return py::make_tuple(g.dims().nx, g.dims().ny, g.dims().nz); })
      .def_property_readonly("wavelengths_um", &VoxelGrid::wavelengths_um)
      .def_property_readonly("voxel_size_m",
                             [](const VoxelGrid& g) { return g.placement().voxel_size_m; })
      .def_property_readonly("origin",
                             [](const VoxelGrid& g) {
                               const Vec3& o = g.placement().origin_m;
                               return py::make_tuple(o.x, o.y, o.z);
                             })
      .def_property_readonly("memory_bytes", &VoxelGrid::memory_bytes);
}

}  // namespace obscura::python
