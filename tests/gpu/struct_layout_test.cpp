// The sizes and offsets of the structs that cross to a CUDA device
// (gpu/struct_layout.h), as the host compiler lays them out: the numbers the
// GPU check (gpu/check, case layout) compares with what device code sees.
#include "obscura/gpu/struct_layout.h"

#include <gtest/gtest.h>

namespace obscura {
namespace {

TEST(StructLayout, WhatCrossesToTheDeviceIsLaidOutAsDeclared) {
  std::uint64_t v[kStructLayoutValues];
  struct_layout(v);
  const std::uint64_t expected[kStructLayoutValues] = {
      24,  72,  48,  208, 96,  104, 128, 136, 144, 152, 160,  // Vec3, Mat3, BBox3, LatticeView
      32,  16,                                                // PlanckTableView
      56,  48,                                                // MarchRay
      336, 208, 280, 296, 312,                                // MarchJob
      256, 216, 232,                                          // SunDepthJob
      12};
  for (int i = 0; i < kStructLayoutValues; ++i)
    EXPECT_EQ(v[i], expected[i]) << kStructLayoutNames[i];
}

}  // namespace
}  // namespace obscura
