// Warnings for sensor bands beyond the clouds' spectral samples
// (scene/spectral_coverage.h).
#include "obscura/scene/spectral_coverage.h"

#include <gtest/gtest.h>

#include <memory>

#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

Scene scene_sampled_at(std::vector<double> wavelengths_um, std::vector<Band> bands) {
  Scene s;
  const std::size_t n = wavelengths_um.size();
  s.medium = std::make_shared<HomogeneousMedium>(
      BBox3{{0, 0, 0}, {1, 1, 1}}, std::move(wavelengths_um), std::vector<double>(n, 0.1),
      std::vector<double>(n, 0.2), std::vector<double>(n, 0.5), 300.0);
  Sensor sensor;
  sensor.name = "seeker";
  sensor.bands = std::move(bands);
  s.sensors.push_back(sensor);
  return s;
}

TEST(SpectralCoverage, AVisibleBandThroughAnInfraredCloudIsNamedWithBothRanges) {
  const auto notes = bands_beyond_cloud_samples(scene_sampled_at(
      {4.0, 10.0}, {Band::preset("visible"), Band::preset("mwir"), Band::flat("far", 14, 16)}));
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("sensor seeker, band visible (0.4-0.7 µm) lies outside the clouds' "
                          "spectral samples (4-10 µm)"),
            std::string::npos)
      << notes[0];
  EXPECT_NE(notes[0].find("held at the 4 µm values"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("band far (14-16 µm)"), std::string::npos) << notes[1];
  EXPECT_NE(notes[1].find("held at the 10 µm values"), std::string::npos) << notes[1];
}

TEST(SpectralCoverage, BandsThatOverlapTheSamplesOrAGreyCloudOrNoCloudGiveNone) {
  // The demo's way: one sample inside each band (0.55 µm in the visible,
  // 10 µm in 8-12 µm), the band's edges beyond the outer samples.
  EXPECT_TRUE(bands_beyond_cloud_samples(
                  scene_sampled_at({0.55, 1.064, 4.0, 10.0},
                                   {Band::preset("visible"), Band::preset("laser1064"),
                                    Band::preset("mwir"), Band::preset("lwir")}))
                  .empty());
  EXPECT_TRUE(
      bands_beyond_cloud_samples(scene_sampled_at({10.0}, {Band::preset("visible")})).empty());
  Scene none = scene_sampled_at({4.0, 10.0}, {Band::preset("visible")});
  none.medium.reset();
  EXPECT_TRUE(bands_beyond_cloud_samples(none).empty());
}

}  // namespace
}  // namespace obscura
