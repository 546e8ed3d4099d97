// The radiance cache's sun (render/radiance_cache/radiance_cache.h): on a
// homogeneous cloud the optical depth towards the sun, interpolated from the
// records as the camera march reads it, is exact up to the cloud's faces.
// The rim nodes just outside the faces hold 2 τ(face) − τ(inner neighbour)
// (lattice_view.h, rim_face); holding τ at the rim node itself (zero outside
// a sunlit face) read the sun's depth at the face as half the first node's.
#include "obscura/render/radiance_cache/radiance_cache.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

TEST(RadianceCache, TheSunsDepthIsExactUpToTheCloudsFaces) {
  constexpr int n = 8;
  constexpr double h = 0.25;
  GridPlacement placement;
  placement.origin_m = {-1, -1, 0};
  placement.voxel_size_m = h;
  auto grid =
      std::make_shared<VoxelGrid>(GridDims{n, n, n}, placement, std::vector<double>{0.5, 0.7});
  for (int s = 0; s < 2; ++s) {
    std::fill_n(grid->sigma_a(s), grid->dims().count(), 0.4f + 0.2f * s);
    std::fill_n(grid->sigma_s(s), grid->dims().count(), 1.2f);
    std::fill_n(grid->g(s), grid->dims().count(), 0.5f);
  }
  Scene scene;
  scene.medium = std::make_shared<GridMedium>(grid);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 35.0;
  scene.sun.azimuth_deg = 20.0;
  scene.sky = Sky::blackbody(0.0, false);
  scene.settings.radiance_cache.photons_per_node = 1000;
  scene.settings.threads = 2;
  const SpectralNodes band(BandQuadrature(Band::flat("b", 0.55, 0.65), 1, 0.0),
                           scene.medium->wavelengths_um());
  const std::vector<SpectralNode> nodes(band.nodes());
  const RadianceCache cache(scene, nodes);
  ASSERT_TRUE(cache.volume().has_medium());
  const SpectralLerp lerp = nodes[0].lerp();
  const float* records = cache.volume().records(0);
  const auto stride = static_cast<std::size_t>(cache.volume().stride());
  const Vec3 to_sun = scene.sun.direction();
  const Vec3 centre(0, 0, 1);
  int lit_face_points = 0;
  // Points from each face's middle inwards, through the half cell between
  // the face and the first nodes (deeper, the sun's ray from a node may leave
  // through another face than from its neighbour, and τ_sun has a kink that
  // no interpolation follows).
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      Vec3 normal(0, 0, 0);
      normal[axis] = side;
      for (const double depth : {0.0, 0.01, 0.04, 0.08, 0.125}) {
        Vec3 p = centre + normal * (1.0 - depth);
        p[(axis + 1) % 3] += 0.15;
        p[(axis + 2) % 3] -= 0.1;
        std::array<std::size_t, 8> slot;
        std::array<double, 8> w;
        ASSERT_TRUE(cache.lattice().corners(p, slot, w));
        double interpolated = 0.0;
        for (int c = 0; c < 8; ++c)
          if (slot[c] != NodeLattice::kNoSlot)
            interpolated += w[c] * records[slot[c] * stride + record::kTauSun];
        std::vector<double> tau(2, 0.0);
        scene.medium->add_optical_depth(Ray{p, to_sun}, 0.0, 1e30, tau.data());
        const double exact = lerp(tau.data());
        lit_face_points += dot(normal, to_sun) > 0.0 && depth == 0.0;
        EXPECT_NEAR(interpolated, exact, 1e-5 + 1e-5 * exact)
            << "face " << axis << (side > 0 ? '+' : '-') << " depth " << depth << " m";
      }
    }
  EXPECT_EQ(lit_face_points, 3);  // the sun's side of the cube is checked too
}

}  // namespace
}  // namespace obscura
