#include "obscura/scene/atmosphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/error.h"
#include "obscura/scene/surface.h"

namespace obscura {
namespace {

TEST(Atmosphere, ExtinctionByBandNameWithWildcard) {
  Atmosphere a;
  a.enabled = true;
  a.extinction_per_m = {{"lwir", 1e-4}, {"*", 3e-4}};
  EXPECT_DOUBLE_EQ(a.extinction_for(Band::preset("lwir")), 1e-4);
  EXPECT_DOUBLE_EQ(a.extinction_for(Band::preset("mwir")), 3e-4);
  EXPECT_DOUBLE_EQ(a.transmittance(Band::preset("lwir"), 2000.0), std::exp(-0.2));
  a.extinction_per_m.erase("*");
  EXPECT_THROW(a.extinction_for(Band::preset("mwir")), Error);
  a.enabled = false;
  EXPECT_EQ(a.transmittance(Band::preset("lwir"), 2000.0), 1.0);
}

TEST(SurfaceMaterial, EmissivityTableInterpolatesAndHoldsEnds) {
  SurfaceMaterial m{300.0, 0.5, {{1.0, 0.2}, {3.0, 0.6}, {10.0, 0.9}}};
  EXPECT_DOUBLE_EQ(m.emissivity_at(0.5), 0.2);
  EXPECT_DOUBLE_EQ(m.emissivity_at(2.0), 0.4);
  EXPECT_DOUBLE_EQ(m.emissivity_at(3.0), 0.6);
  EXPECT_DOUBLE_EQ(m.emissivity_at(12.0), 0.9);
  EXPECT_DOUBLE_EQ(m.reflectance_at(2.0), 0.6);
  const SurfaceMaterial grey{300.0, 0.7};
  EXPECT_DOUBLE_EQ(grey.emissivity_at(4.0), 0.7);
}

}  // namespace
}  // namespace obscura
