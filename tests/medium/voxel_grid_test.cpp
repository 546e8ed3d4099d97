#include "obscura/medium/voxel_grid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/error.h"

namespace obscura {
namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VoxelGrid, RejectsZeroSizedGrids) {
  const std::string m = message_of([] { VoxelGrid({0, 4, 4}, {}, {10.0}, "cloud.vdb"); });
  EXPECT_NE(m.find("cloud.vdb"), std::string::npos) << m;
  EXPECT_NE(m.find("dims"), std::string::npos) << m;
  EXPECT_NE(m.find("> 0"), std::string::npos) << m;
}

TEST(VoxelGrid, RejectsDimsWhoseProductOverflows) {
  const int big = 2000000000;
  const std::string m = message_of([&] { VoxelGrid({big, big, big}, {}, {10.0}, "huge.vdb"); });
  EXPECT_NE(m.find("overflows"), std::string::npos) << m;
}

TEST(VoxelGrid, RejectsGridsLargerThanAvailableMemory) {
  // 100000³ × 4 channels × 4 bytes = 16 PB: representable, but no machine has it.
  const std::string m = message_of([] {
    VoxelGrid({100000, 100000, 100000}, {}, {10.0}, "big.vdb");
  });
  EXPECT_NE(m.find("available"), std::string::npos) << m;
  EXPECT_NE(m.find("big.vdb"), std::string::npos) << m;
}

TEST(VoxelGrid, ValidateNamesTheChannelAndVoxel) {
  VoxelGrid g({2, 2, 2}, {}, {4.0, 10.0}, "c.vdb");
  for (std::size_t v = 0; v < 8; ++v) g.temperature()[v] = 300;
  EXPECT_NO_THROW(g.validate("c.vdb"));
  g.sigma_s(1)[g.index(1, 0, 1)] = -0.5f;
  std::string m = message_of([&] { g.validate("c.vdb"); });
  EXPECT_NE(m.find("sigma_s_001 voxel (1,0,1)"), std::string::npos) << m;
  EXPECT_NE(m.find("negative"), std::string::npos) << m;
  g.sigma_s(1)[g.index(1, 0, 1)] = 0.5f;
  g.sigma_a(0)[g.index(0, 1, 0)] = std::nanf("");
  m = message_of([&] { g.validate("c.vdb"); });
  EXPECT_NE(m.find("sigma_a_000 voxel (0,1,0)"), std::string::npos) << m;
  EXPECT_NE(m.find("not finite"), std::string::npos) << m;
  g.sigma_a(0)[g.index(0, 1, 0)] = 0.5f;
  g.g(0)[0] = 1.0f;
  m = message_of([&] { g.validate("c.vdb"); });
  EXPECT_NE(m.find("g_000"), std::string::npos) << m;
  EXPECT_NE(m.find("(-1, 1)"), std::string::npos) << m;
}

TEST(VoxelGrid, WorldBoundsCoverTheCells) {
  GridPlacement p;
  p.origin_m = {1, 2, 3};
  p.voxel_size_m = 0.5;
  VoxelGrid g({4, 6, 8}, p, {10.0});
  const BBox3 b = g.world_bounds();
  EXPECT_NEAR(b.lo.x, 1, 1e-12);
  EXPECT_NEAR(b.hi.x, 3, 1e-12);
  EXPECT_NEAR(b.hi.y, 5, 1e-12);
  EXPECT_NEAR(b.hi.z, 7, 1e-12);
  // Voxel centre (0,0,0) sits half a voxel inside the corner.
  const Vec3 c = p.index_to_world({0, 0, 0});
  EXPECT_NEAR(c.x, 1.25, 1e-12);
  const Vec3 back = p.world_to_index(c);
  EXPECT_NEAR(length(back), 0, 1e-12);
}

}  // namespace
}  // namespace obscura
