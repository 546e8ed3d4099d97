// A Wavefront OBJ triangle mesh (a target or a building).
#include "harness.h"
#include "obscura/io/obj_mesh.h"

OBSCURA_FUZZ_HARNESS(obj_mesh) {
  obscura::read_obj_mesh(obscura::fuzz::scratch_file("mesh.obj", bytes));
}
