// The target mask (analysis/target_mask.h): pixel-centre rays against the
// surfaces, the first hit decides; the background frame around the target's
// bounding box, clipped to the image.
#include "obscura/analysis/target_mask.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/input_error.h"

namespace obscura {
namespace {

// A 100×100 camera 10 m in front of the plane y = 0, looking along +y, whose
// pixels are exactly 0.1 m wide there (tan(fov/2) = 0.5): pixel centres fall
// at x, z = ±0.05, ±0.15, …, never on a box edge at a multiple of 0.1 m.
Sensor square_camera() {
  Sensor s;
  s.name = "cam";
  const double fov = 2.0 * std::atan(0.5) * 180.0 / std::numbers::pi;
  s.camera = PinholeCamera({0, -10, 0}, {0, 0, 0}, {0, 0, 1}, fov, 100, 100);
  s.bands = {Band::preset("lwir")};
  return s;
}

std::unique_ptr<Surface> box(const std::string& name, Vec3 lo, Vec3 hi, bool target) {
  auto b = std::make_unique<BoxSurface>(name, SurfaceMaterial{300.0, 1.0}, BBox3(lo, hi));
  b->set_target(target);
  return b;
}

TEST(TargetMask, PixelCountIsTheBoxsProjectedArea) {
  Scene scene;
  scene.sensors.push_back(square_camera());
  // A 2 m × 2 m face at 10 m: 20 × 20 pixels of 0.1 m; the box's depth hides
  // behind its front face (the camera is on its axis).
  scene.surfaces.push_back(box("target", {-1, 0, -1}, {1, 2, 1}, true));
  EXPECT_TRUE(scene_has_target(scene));
  const TargetMask m = compute_target_mask(scene, scene.sensors[0], 8, 2);
  EXPECT_EQ(m.sensor, "cam");
  EXPECT_EQ(m.target_pixels, 400);
  EXPECT_EQ(m.x0, 40);
  EXPECT_EQ(m.x1, 60);
  EXPECT_EQ(m.y0, 40);
  EXPECT_EQ(m.y1, 60);
  // The frame: the 36 × 36 box around it less the target.
  EXPECT_EQ(m.background_pixels, 36 * 36 - 400);
  EXPECT_EQ(m.at(50, 50), MaskLabel::kTarget);
  EXPECT_EQ(m.at(32, 32), MaskLabel::kBackground);
  EXPECT_EQ(m.at(67, 50), MaskLabel::kBackground);
  EXPECT_EQ(m.at(68, 50), MaskLabel::kOther);
  EXPECT_EQ(m.at(31, 40), MaskLabel::kOther);
}

TEST(TargetMask, BackgroundFrameIsClippedToTheImage) {
  Scene scene;
  scene.sensors.push_back(square_camera());
  scene.surfaces.push_back(box("target", {-1, 0, -1}, {1, 2, 1}, true));
  const TargetMask m = compute_target_mask(scene, scene.sensors[0], 45);
  EXPECT_EQ(m.target_pixels, 400);
  EXPECT_EQ(m.background_pixels, 100 * 100 - 400);
}

TEST(TargetMask, TheFirstSurfaceHitDecides) {
  Scene scene;
  scene.sensors.push_back(square_camera());
  scene.surfaces.push_back(box("target", {-1, 0, -1}, {1, 2, 1}, true));
  // A non-target wall in front of the target's left half (x < 0), and a
  // ground behind everything: neither is target.
  scene.surfaces.push_back(box("wall", {-3, -3, -3}, {0, -2, 3}, false));
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{290.0, 1.0}, -1.5));
  const TargetMask m = compute_target_mask(scene, scene.sensors[0], 8);
  EXPECT_EQ(m.target_pixels, 200);
  EXPECT_EQ(m.x0, 50);
  EXPECT_EQ(m.x1, 60);
  EXPECT_EQ(m.background_pixels, (10 + 16) * 36 - 200);
}

TEST(TargetMask, NoTargetInViewGivesAnEmptyMask) {
  Scene scene;
  Sensor s = square_camera();
  s.camera = PinholeCamera({0, -10, 0}, {0, -20, 0}, {0, 0, 1}, 30, 40, 30);  // looking away
  scene.sensors.push_back(s);
  scene.surfaces.push_back(box("target", {-1, 0, -1}, {1, 2, 1}, true));
  const TargetMask m = compute_target_mask(scene, scene.sensors[0], 8);
  EXPECT_TRUE(m.empty());
  EXPECT_EQ(m.background_pixels, 0);
  EXPECT_EQ(m.x1, 0);
  EXPECT_EQ(m.labels.size(), 40u * 30u);

  Scene no_target;
  no_target.surfaces.push_back(box("plain", {-1, 0, -1}, {1, 2, 1}, false));
  EXPECT_FALSE(scene_has_target(no_target));
}

TEST(TargetMask, FrameOnAHandMadeMaskWithAHole) {
  // 8 × 5 pixels; target pixels at (2..4, 1) and (2, 2), (4, 2): the box is
  // x 2..4, y 1..2; (3, 2) is a hole inside it, background.
  TargetMask m;
  m.sensor = "s";
  m.width = 8;
  m.height = 5;
  m.labels.assign(40, MaskLabel::kBackground);  // stale labels are reset
  const std::pair<int, int> targets[] = {{2, 1}, {3, 1}, {4, 1}, {2, 2}, {4, 2}};
  for (auto [x, y] : targets) m.labels[y * 8 + x] = MaskLabel::kTarget;
  finish_target_mask(m, 1);
  EXPECT_EQ(m.target_pixels, 5);
  EXPECT_EQ(m.x0, 2);
  EXPECT_EQ(m.y0, 1);
  EXPECT_EQ(m.x1, 5);
  EXPECT_EQ(m.y1, 3);
  // Grown by 1: x 1..5, y 0..3 → 5 × 4 = 20 pixels, 5 of them target.
  EXPECT_EQ(m.background_pixels, 15);
  EXPECT_EQ(m.at(3, 2), MaskLabel::kBackground);
  EXPECT_EQ(m.at(0, 0), MaskLabel::kOther);
  EXPECT_EQ(m.at(6, 4), MaskLabel::kOther);
  EXPECT_EQ(m.at(5, 3), MaskLabel::kBackground);

  const auto e = testing::expect_input_error([&] { finish_target_mask(m, -1); });
  EXPECT_EQ(e.field(), "background_margin_px");
}

}  // namespace
}  // namespace obscura
