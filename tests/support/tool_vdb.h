#pragma once
// VDB files written with OpenVDB's own API the way smoke and explosion tools
// write them (Houdini's pyro, Blender's Mantaflow cache, EmberGen): several
// fog-volume float grids per file ("density", "temperature", "flame"), a
// velocity vector grid, a linear transform of voxel size and translation,
// sparse trees with only the smoke's voxels active, optionally stored as
// 16-bit halves (Blender's "half" precision). For the vdb-density cloud's
// tests (io/vdb_density_file.h, scene/vdb_density_cloud.h).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <functional>
#include <string>

namespace obscura::testing {

// Houdini's default: 0.1 m voxels, index (0,0,0) centred at `translation_m`.
inline openvdb::math::Transform::Ptr tool_transform(double voxel_m = 0.1,
                                                    openvdb::Vec3d translation_m = {1.5, -2.0,
                                                                                    0.25}) {
  auto xf = openvdb::math::Transform::createLinearTransform(voxel_m);
  xf->postTranslate(translation_m);
  return xf;
}

// A fog-volume float grid whose active voxels are `box` (inclusive index
// bounds), each holding value(i, j, k); every other voxel is the background.
inline openvdb::FloatGrid::Ptr tool_grid(const std::string& name,
                                         const openvdb::math::Transform::Ptr& xf,
                                         const openvdb::CoordBBox& box,
                                         const std::function<float(int, int, int)>& value,
                                         float background = 0.0f) {
  openvdb::initialize();
  auto g = openvdb::FloatGrid::create(background);
  g->setName(name);
  g->setTransform(xf->copy());
  g->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto acc = g->getAccessor();
  for (auto it = box.begin(); it; ++it) {
    const openvdb::Coord c = *it;
    acc.setValueOn(c, value(c.x(), c.y(), c.z()));
  }
  return g;
}

// Adds the voxels of a second blob to `g`.
inline void add_blob(openvdb::FloatGrid& g, const openvdb::CoordBBox& box,
                     const std::function<float(int, int, int)>& value) {
  auto acc = g.getAccessor();
  for (auto it = box.begin(); it; ++it) {
    const openvdb::Coord c = *it;
    acc.setValueOn(c, value(c.x(), c.y(), c.z()));
  }
}

// A velocity grid, as every solver writes beside its scalars.
inline openvdb::Vec3SGrid::Ptr tool_velocity(const openvdb::math::Transform::Ptr& xf,
                                             const openvdb::CoordBBox& box) {
  auto g = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
  g->setName("vel");
  g->setTransform(xf->copy());
  g->fill(box, openvdb::Vec3s(0.0f, 0.0f, 1.5f));
  return g;
}

inline void write_tool_vdb(const std::filesystem::path& path, const openvdb::GridPtrVec& grids) {
  openvdb::io::File f(path.string());
  f.write(grids);
  f.close();
}

}  // namespace obscura::testing
