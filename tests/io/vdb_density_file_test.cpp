// Other tools' VDB files read as density volumes (io/vdb_density_file.h):
// the grids over the density's active bounding box, the transform's voxel
// size and translation, half floats, and every refusal naming the file and
// the grid.
#include "obscura/io/vdb_density_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "obscura/core/memory_limit.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"
#include "support/tool_vdb.h"

namespace obscura {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using testing::contains;
using testing::expect_input_error;
using testing::tool_grid;
using testing::tool_transform;
using testing::write_tool_vdb;

float density_at(int i, int j, int k) { return 0.01f * static_cast<float>(1 + i + 2 * j + 3 * k); }
float temperature_at(int i, int j, int k) { return 300.0f + static_cast<float>(i - j + k); }

class VdbDensityFile : public testing::TempDirTest {
 protected:
  // Houdini's pyro output: density, temperature and flame grids and a
  // velocity field, the smoke well away from the index origin.
  std::filesystem::path houdini_file(const CoordBBox& box) {
    const auto xf = tool_transform();
    const std::filesystem::path p = dir_ / "explosion.vdb";
    write_tool_vdb(p, {tool_grid("density", xf, box, density_at),
                       tool_grid("temperature", xf, box.expandBy(1), temperature_at),
                       tool_grid("flame", xf, box, [](int, int, int) { return 0.5f; }),
                       testing::tool_velocity(xf, box)});
    return p;
  }
  // A density grid of 0.25 m voxels with two blobs 40000 voxels apart, far
  // from the index origin.
  static openvdb::FloatGrid::Ptr two_far_blobs() {
    auto density = tool_grid("density", tool_transform(0.25),
                             CoordBBox(Coord(-2000, 500, 900), Coord(-1997, 503, 903)), density_at);
    testing::add_blob(*density, CoordBBox(Coord(38000, 502, 900), Coord(38003, 505, 901)),
                      density_at);
    return density;
  }
  std::string error_of(const std::filesystem::path& p, const std::string& density = "density",
                       const std::string& temperature = "") {
    const InputError e = expect_input_error([&] { read_vdb_density(p, density, temperature); });
    EXPECT_EQ(e.file(), p.string());
    return e.what();
  }
};

TEST_F(VdbDensityFile, ReadsTheActiveBoxWithTheToolsTransform) {
  const CoordBBox box(Coord(10, -4, 20), Coord(17, 3, 25));
  const auto p = houdini_file(box);
  const VdbDensityVolume v = read_vdb_density(p, "density", "temperature");
  EXPECT_FALSE(v.empty);
  EXPECT_EQ(v.dims, (GridDims{8, 8, 6}));
  EXPECT_EQ(v.index_min[0], 10);
  EXPECT_EQ(v.index_min[1], -4);
  EXPECT_EQ(v.index_min[2], 20);
  // Voxel (i,j,k) of the arrays is OpenVDB's (10+i, -4+j, 20+k), centred
  // where the transform puts it: 0.1 m voxels translated by (1.5, -2, 0.25).
  EXPECT_NEAR(v.placement.voxel_size_m, 0.1, 1e-15);
  const auto xf = tool_transform();
  for (const auto& [i, j, k] : {std::tuple{0, 0, 0}, std::tuple{7, 7, 5}, std::tuple{3, 1, 4}}) {
    const openvdb::Vec3d w = xf->indexToWorld(Coord(10 + i, -4 + j, 20 + k));
    const Vec3 ours = v.placement.index_to_world(Vec3(i, j, k));
    EXPECT_NEAR(ours.x, w.x(), 1e-12);
    EXPECT_NEAR(ours.y, w.y(), 1e-12);
    EXPECT_NEAR(ours.z, w.z(), 1e-12);
    const std::size_t at = static_cast<std::size_t>(i + 8 * (j + 8 * k));
    EXPECT_EQ(v.density[at], density_at(10 + i, -4 + j, 20 + k));
    EXPECT_EQ(v.temperature[at], temperature_at(10 + i, -4 + j, 20 + k));
  }
}

TEST_F(VdbDensityFile, WithoutATemperatureGridOnlyTheDensityIsRead) {
  const auto p = houdini_file(CoordBBox(Coord(0), Coord(3)));
  const VdbDensityVolume v = read_vdb_density(p, "density", "");
  EXPECT_EQ(v.density.size(), 64u);
  EXPECT_TRUE(v.temperature.empty());
}

TEST_F(VdbDensityFile, ASparseTreeIsReadOverItsActiveBoxNotItsIndexSpace) {
  // Two blobs 40000 voxels apart, far from the index origin: the dense box
  // spans the blobs (the gap between them is zero), nothing else.
  const auto p = dir_ / "sparse.vdb";
  write_tool_vdb(p, {two_far_blobs()});
  const VdbDensityVolume v = read_vdb_density(p, "density", "");
  EXPECT_EQ(v.dims, (GridDims{40004, 6, 4}));
  EXPECT_EQ(v.index_min[0], -2000);
  EXPECT_EQ(v.index_min[1], 500);
  EXPECT_EQ(v.index_min[2], 900);
  const auto at = [&](int x, int y, int z) {
    return v.density[static_cast<std::size_t>((x + 2000) + 40004 * ((y - 500) + 6 * (z - 900)))];
  };
  EXPECT_EQ(at(-2000, 500, 900), density_at(-2000, 500, 900));
  EXPECT_EQ(at(38003, 505, 901), density_at(38003, 505, 901));
  EXPECT_EQ(at(0, 502, 901), 0.0f);      // between the blobs
  EXPECT_EQ(at(-1998, 505, 903), 0.0f);  // in the box, outside both blobs
  // The box's memory (3.8 MB) is checked before it is allocated; the
  // tree's (0.6 MB) fits.
  set_memory_limit(1500000, MemoryLimitSource::kCommandLine);
  const std::string e = error_of(p);
  reset_memory_limit();
  EXPECT_TRUE(contains(e, "density: the active bounding box of 40004x6x4 voxels")) << e;
}

TEST_F(VdbDensityFile, FarClustersAreReadAsPartsWithABorderOfBackground) {
  // The same two blobs 40000 voxels apart: in parts, each blob's box and one
  // voxel of background around it, not the 40004-voxel box between them.
  const auto xf = tool_transform(0.25);
  const openvdb::FloatGrid::Ptr density = two_far_blobs();
  const auto p = dir_ / "sparse.vdb";
  write_tool_vdb(p, {density});
  const std::vector<VdbDensityVolume> parts = read_vdb_density_parts(p, "density", "");
  ASSERT_EQ(parts.size(), 2u);
  const int lows[2][3] = {{-2001, 499, 899}, {37999, 501, 899}};
  const GridDims dims[2] = {{6, 6, 6}, {6, 6, 4}};
  for (int n = 0; n < 2; ++n) {
    const VdbDensityVolume& v = parts[static_cast<std::size_t>(n)];
    EXPECT_EQ(v.dims, dims[n]) << n;
    for (int a = 0; a < 3; ++a) EXPECT_EQ(v.index_min[a], lows[n][a]) << n;
    EXPECT_FALSE(v.empty);
    EXPECT_TRUE(v.temperature.empty());
    // Every voxel is the grid's own value there (background 0 on the border).
    const openvdb::FloatGrid::ConstAccessor acc = density->getConstAccessor();
    for (int k = 0; k < v.dims.nz; ++k)
      for (int j = 0; j < v.dims.ny; ++j)
        for (int i = 0; i < v.dims.nx; ++i) {
          const Coord c(lows[n][0] + i, lows[n][1] + j, lows[n][2] + k);
          ASSERT_EQ(v.density[static_cast<std::size_t>(i + v.dims.nx * (j + v.dims.ny * k))],
                    acc.getValue(c))
              << c;
        }
    // The corner of its lowest voxel, half a voxel below where OpenVDB centres it.
    const openvdb::Vec3d corner =
        xf->indexToWorld(openvdb::Vec3d(lows[n][0], lows[n][1], lows[n][2]) - 0.5);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(v.placement.origin_m[a], corner[a], 1e-9);
  }
}

TEST_F(VdbDensityFile, ActiveTilesAreClusteredLikeTheirVoxels) {
  // Two active tiles of 128³ voxels (as a solver's fill writes a uniform
  // region), 40 tiles apart: a part around each, with its border.
  auto density = openvdb::FloatGrid::create(0.0f);
  density->setName("density");
  density->setTransform(tool_transform());
  density->tree().addTile(2, Coord(0, 0, 0), 0.5f, true);
  density->tree().addTile(2, Coord(128 * 40, 0, 0), 0.25f, true);
  const auto p = dir_ / "tiles.vdb";
  write_tool_vdb(p, {density});
  const std::vector<VdbDensityVolume> parts = read_vdb_density_parts(p, "density", "");
  ASSERT_EQ(parts.size(), 2u);
  for (int n = 0; n < 2; ++n) {
    const VdbDensityVolume& v = parts[static_cast<std::size_t>(n)];
    EXPECT_EQ(v.dims, (GridDims{130, 130, 130}));
    EXPECT_EQ(v.index_min[0], n == 0 ? -1 : 128 * 40 - 1);
    EXPECT_EQ(v.index_min[1], -1);
    const auto at = [&](int i, int j, int k) {
      return v.density[static_cast<std::size_t>(i + 130 * (j + 130 * k))];
    };
    EXPECT_EQ(at(0, 0, 0), 0.0f);  // the border
    EXPECT_EQ(at(1, 1, 1), n == 0 ? 0.5f : 0.25f);
    EXPECT_EQ(at(128, 64, 128), n == 0 ? 0.5f : 0.25f);
    EXPECT_EQ(at(129, 1, 1), 0.0f);
  }
}

TEST_F(VdbDensityFile, ACompactOrNearClusterIsOneBox) {
  // One blob, or two whose boxes would hold over half of the box around
  // both: the one box of read_vdb_density.
  const auto xf = tool_transform();
  auto density = tool_grid("density", xf, CoordBBox(Coord(0), Coord(9)), density_at);
  const auto one = dir_ / "one.vdb";
  write_tool_vdb(one, {density});
  std::vector<VdbDensityVolume> parts = read_vdb_density_parts(one, "density", "");
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].dims, (GridDims{10, 10, 10}));
  EXPECT_EQ(parts[0].density, read_vdb_density(one, "density", "").density);
  testing::add_blob(*density, CoordBBox(Coord(30, 0, 0), Coord(39, 9, 9)), density_at);
  const auto near = dir_ / "near.vdb";
  write_tool_vdb(near, {density});
  parts = read_vdb_density_parts(near, "density", "");
  ASSERT_EQ(parts.size(), 1u);  // 2 × 12³ of 40 × 10 × 10 voxels: over half
  EXPECT_EQ(parts[0].dims, (GridDims{40, 10, 10}));
}

TEST_F(VdbDensityFile, HalfFloatGridsReadAsTheirHalfValues) {
  // Blender's cache writes "half" precision by default.
  const auto xf = tool_transform();
  auto density = tool_grid("density", xf, CoordBBox(Coord(0), Coord(2)),
                           [](int i, int, int) { return 0.1f * static_cast<float>(i + 1); });
  density->setSaveFloatAsHalf(true);
  const auto p = dir_ / "fluid_data_0001.vdb";
  write_tool_vdb(p, {density});
  const VdbDensityVolume v = read_vdb_density(p, "density", "");
  EXPECT_EQ(v.density[0], static_cast<float>(openvdb::math::half(0.1f)));
  EXPECT_EQ(v.density[2], static_cast<float>(openvdb::math::half(0.3f)));
  EXPECT_NE(v.density[0], 0.1f);  // the file held halves
}

TEST_F(VdbDensityFile, AnEmptyDensityGridIsOneEmptyVoxel) {
  const auto p = dir_ / "first_frame.vdb";
  auto density = openvdb::FloatGrid::create(0.0f);
  density->setName("density");
  density->setTransform(tool_transform());
  write_tool_vdb(p, {density});
  const VdbDensityVolume v = read_vdb_density(p, "density", "");
  EXPECT_TRUE(v.empty);
  EXPECT_EQ(v.dims, (GridDims{1, 1, 1}));
  EXPECT_EQ(v.density, std::vector<float>{0.0f});
}

TEST_F(VdbDensityFile, AMissingGridNamesTheFilesGrids) {
  const auto p = houdini_file(CoordBBox(Coord(0), Coord(3)));
  const std::string e = error_of(p, "smoke");
  EXPECT_TRUE(contains(e,
                       "explosion.vdb: smoke: no grid of that name (the file's grids: "
                       "density, flame, temperature, vel); the scene's \"density_grid\""))
      << e;
  EXPECT_TRUE(contains(error_of(p, "density", "heat"), "heat: no grid of that name"));
}

TEST_F(VdbDensityFile, AVectorGridIsNotADensity) {
  const auto p = houdini_file(CoordBBox(Coord(0), Coord(3)));
  const std::string e = error_of(p, "vel");
  EXPECT_TRUE(contains(e, "vel: grid holds vec3s values, expected a float grid")) << e;
}

TEST_F(VdbDensityFile, ALevelSetIsNotADensity) {
  auto sdf = openvdb::FloatGrid::create(0.0f);
  sdf->setName("surface");
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  const auto p = dir_ / "collider.vdb";
  write_tool_vdb(p, {sdf});
  EXPECT_TRUE(contains(error_of(p, "surface"), "surface: grid is a level set"));
}

TEST_F(VdbDensityFile, NonUniformVoxelsAreRefused) {
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  m(0, 0) = 0.1;
  m(1, 1) = 0.1;
  m(2, 2) = 0.2;
  const auto xf = openvdb::math::Transform::createLinearTransform(m);
  const auto p = dir_ / "stretched.vdb";
  write_tool_vdb(p, {tool_grid("density", xf, CoordBBox(Coord(0), Coord(1)), density_at)});
  const std::string e = error_of(p);
  EXPECT_TRUE(contains(e,
                       "stretched.vdb: density: transform has non-uniform voxel size "
                       "(0.1, 0.1, 0.2) m; obscura reads cubic voxels only"))
      << e;
}

TEST_F(VdbDensityFile, AFrustumTransformIsRefused) {
  const openvdb::BBoxd frustum(openvdb::Vec3d(0), openvdb::Vec3d(8));
  const auto xf = openvdb::math::Transform::createFrustumTransform(frustum, 0.5, 10.0, 0.1);
  const auto p = dir_ / "frustum.vdb";
  write_tool_vdb(p, {tool_grid("density", xf, CoordBBox(Coord(0), Coord(1)), density_at)});
  EXPECT_TRUE(contains(error_of(p), "density: transform is a non-linear"));
}

TEST_F(VdbDensityFile, ANonZeroBackgroundIsRefused) {
  const auto p = dir_ / "fogged.vdb";
  write_tool_vdb(
      p, {tool_grid("density", tool_transform(), CoordBBox(Coord(0), Coord(1)), density_at, 0.2f)});
  EXPECT_TRUE(contains(error_of(p), "density: background value 0.2"));
}

TEST_F(VdbDensityFile, TheTemperatureMustLieOnTheDensitysVoxels) {
  const CoordBBox box(Coord(0), Coord(2));
  const auto p = dir_ / "shifted.vdb";
  write_tool_vdb(p, {tool_grid("density", tool_transform(), box, density_at),
                     tool_grid("temperature", tool_transform(0.2), box, temperature_at)});
  EXPECT_TRUE(contains(error_of(p, "density", "temperature"),
                       "temperature: grid transform differs from the density grid 'density''s"));
}

TEST_F(VdbDensityFile, CorruptFilesAreRefusedBeforeOpenVdbReadsThem) {
  const auto p = houdini_file(CoordBBox(Coord(0), Coord(7)));
  std::filesystem::resize_file(p, std::filesystem::file_size(p) - 10);
  EXPECT_TRUE(contains(error_of(p), "truncated")) << error_of(p);
  std::ofstream(dir_ / "text.vdb") << "not a vdb file at all";
  EXPECT_TRUE(contains(error_of(dir_ / "text.vdb"), "not an OpenVDB file"));
  EXPECT_TRUE(contains(error_of(dir_ / "absent.vdb"), "no such file"));
}

}  // namespace
}  // namespace obscura
