// A VTK legacy STRUCTURED_POINTS frame (ASCII or BINARY), read as prepare
// reads CFD output: concentration alone, then with a temperature array.
#include "harness.h"
#include "obscura/io/vtk_structured_points.h"

OBSCURA_FUZZ_HARNESS(vtk_legacy) {
  const auto path = obscura::fuzz::scratch_file("frame.vtk", bytes);
  obscura::fuzz::ignore_input_errors([&] { obscura::read_vtk_structured_points(path, 0.0); });
  obscura::VtkArrayNames with_temperature;
  with_temperature.temperature = "temperature";
  obscura::read_vtk_structured_points(path, 0.0, with_temperature);
}
