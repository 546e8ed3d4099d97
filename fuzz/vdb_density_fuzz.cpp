// Another tool's VDB file (Houdini, Blender, EmberGen) read as a frame of a
// vdb-density cloud (io/vdb_density_file.h): the walk over the whole file,
// then OpenVDB reading the density and temperature grids over the density's
// active box, or over its clusters' boxes (a static cloud's parts). Read
// three times: whole with the temperature grid, whole and in parts without
// it, so that a mutation that breaks only the temperature still has the
// density read.
#include "harness.h"
#include "obscura/io/vdb_density_file.h"

OBSCURA_FUZZ_HARNESS(vdb_density) {
  const auto path = obscura::fuzz::scratch_file("explosion.vdb", bytes);
  obscura::fuzz::ignore_input_errors(
      [&] { obscura::read_vdb_density(path, "density", "temperature"); });
  obscura::read_vdb_density(path, "density", "");
  obscura::read_vdb_density_parts(path, "density", "");
}
