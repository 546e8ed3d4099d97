// Writes the vdb_density harness's seeds (fuzz/vdb_density_fuzz.cpp) into
// the folder named by its argument: VDB files as smoke tools write them,
// through the tests' helpers (tests/support/tool_vdb.h). fuzz/make-corpus
// builds and runs it; it is not part of the build.
#include "support/tool_vdb.h"
using namespace obscura::testing;
using openvdb::Coord;
using openvdb::CoordBBox;
int main(int, char** argv) {
  openvdb::initialize();
  const std::string dir = argv[1];
  {  // Houdini pyro: density, temperature, flame, vel; two blobs far apart
    const auto xf = tool_transform(0.1, {1.5, -2.0, 0.25});
    auto d = tool_grid("density", xf, CoordBBox(Coord(-40, 0, 0), Coord(-36, 3, 4)),
                       [](int i, int j, int k) {
                         return 0.05f * static_cast<float>(1 + ((i + j + k) % 7 + 7) % 7);
                       });
    add_blob(*d, CoordBBox(Coord(300, 2, 1), Coord(302, 5, 3)), [](int, int, int) { return 0.3f; });
    auto t = tool_grid("temperature", xf, CoordBBox(Coord(-40, 0, 0), Coord(-37, 2, 2)),
                       [](int i, int, int) { return 0.1f * (i + 41); });
    auto f = tool_grid("flame", xf, CoordBBox(Coord(-39, 1, 1), Coord(-38, 2, 2)),
                       [](int, int, int) { return 0.7f; });
    write_tool_vdb(dir + "/houdini_pyro.vdb",
                   {d, t, f, tool_velocity(xf, CoordBBox(Coord(-40, 0, 0), Coord(-38, 1, 1)))});
  }
  {  // Blender Mantaflow cache: half floats
    const auto xf = tool_transform(0.25, {0.0, 0.0, 0.0});
    auto d = tool_grid("density", xf, CoordBBox(Coord(0), Coord(5)),
                       [](int i, int j, int k) { return 0.01f * (i * j + k); });
    d->setSaveFloatAsHalf(true);
    auto t = tool_grid("temperature", xf, CoordBBox(Coord(0), Coord(5)),
                       [](int i, int, int) { return 290.0f + i; });
    t->setSaveFloatAsHalf(true);
    write_tool_vdb(dir + "/blender_half.vdb", {d, t});
  }
}
