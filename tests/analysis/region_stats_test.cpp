#include "obscura/analysis/region_stats.h"

#include <gtest/gtest.h>

#include "obscura/core/planck.h"

namespace obscura {
namespace {

TEST(RegionStats, MeansOverRectanglesAndTheWholeImage) {
  SensorImage img;
  img.sensor = "ir";
  img.width = 4;
  img.height = 2;
  const Band lwir = Band::preset("lwir");
  const BandQuadrature q(lwir, 8, 0.0);
  BandImage b{lwir, std::vector<float>(8), std::vector<float>(8), std::vector<float>(8), {}};
  for (int i = 0; i < 8; ++i) {
    b.radiance[i] = static_cast<float>(q.blackbody_radiance(i < 4 ? 300.0 : 280.0));
    b.transmittance[i] = 0.1f * i;
  }
  img.bands.push_back(b);
  const std::vector<PixelRegion> regions = {
      {"top", "ir", 0, 0, 4, 1}, {"other", "tv", 0, 0, 1, 1}, {"corner", "ir", 3, 1, 4, 2}};
  const auto stats = region_stats(img, regions, RenderSettings{});
  ASSERT_EQ(stats.size(), 3u);  // image, top, corner (the "tv" region belongs to another sensor)
  EXPECT_EQ(stats[0].region, "image");
  EXPECT_EQ(stats[0].pixels, 8);
  EXPECT_NEAR(stats[0].mean_transmittance, 0.35, 1e-6);
  EXPECT_EQ(stats[1].region, "top");
  EXPECT_NEAR(stats[1].mean_apparent_temperature, 300.0, 1e-3);  // uniform blackbody region
  EXPECT_NEAR(stats[1].mean_transmittance, 0.15, 1e-6);
  EXPECT_EQ(stats[2].region, "corner");
  EXPECT_NEAR(stats[2].mean_apparent_temperature, 280.0, 1e-3);
  EXPECT_NEAR(stats[2].mean_transmittance, 0.7, 1e-6);
}

}  // namespace
}  // namespace obscura
