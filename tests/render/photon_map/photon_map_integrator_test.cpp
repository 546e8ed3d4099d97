// The photon-map integrator against truths and against the path tracer:
// furnace and equilibrium (hybrid and pure forms) and a slab through `validate` (2 %,
// issue #4), the two study scenes against a path-traced reference image, and
// thread independence.
#include "obscura/render/photon_map/photon_map_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "obscura/render/renderer.h"
#include "obscura/scene/example_scenes.h"
#include "obscura/validation/validation_cases.h"
#include "support/image_error.h"
#include "support/render_helpers.h"

namespace obscura {
namespace {

ValidationOptions photon_map_options(long long photons) {
  ValidationOptions o;
  o.settings.method = RenderMethod::kPhotonMap;
  o.settings.photon_map.photons_per_node = photons;
  o.samples = 20000;
  return o;
}

TEST(PhotonMapIntegrator, FurnaceAndEquilibriumInBothForms) {
  for (const auto& r : validate_furnace(1.0, 0.5, photon_map_options(200000)))
    EXPECT_TRUE(r.pass) << r.quantity << " " << r.obtained << " ± " << r.stderr_mean;
  for (const auto& r : validate_furnace(3.0, 0.85, photon_map_options(200000)))
    EXPECT_TRUE(r.pass) << r.quantity << " " << r.obtained << " ± " << r.stderr_mean;
  for (const auto& r : validate_equilibrium(0.8, 1.0, 0.5, 300.0, photon_map_options(200000)))
    EXPECT_TRUE(r.pass) << r.quantity << " " << r.obtained << " ± " << r.stderr_mean;
  // The paper's pure form: all in-scattering, single included, from photons.
  ValidationOptions pure = photon_map_options(200000);
  pure.settings.photon_map.pure = true;
  for (const auto& r : validate_furnace(1.0, 0.5, pure))
    EXPECT_TRUE(r.pass) << r.quantity << " " << r.obtained << " ± " << r.stderr_mean;
}

TEST(PhotonMapIntegrator, SlabOfModerateThicknessAgainstDisort) {
  // half-width 20 m (edge loss < 0.5 % here, docs/validation.md).
  const SlabSpec slab{0.9, 1.0, 0.5, SlabIncidence::kCollimated, 1.0, 20.0};
  const SlabReference ref{0.129793276, 0.739091109, 0.367879441, "DISORT"};
  for (const auto& r : validate_slab(slab, ref, photon_map_options(1000000)))
    EXPECT_TRUE(r.pass) << r.quantity << " " << r.obtained << " ± " << r.stderr_mean << " vs "
                        << r.reference;
}

// Issue #4 asks for 2 % on both scenes. Measured at this size (16×12 px, 48³
// puff) after the sun-photon fix of 2026-11-23 (shaded disc points no longer
// dropped): LWIR 0.0 %; visible 3.0 % with 1e6 photons, 1.8 % with 3e6
// (before the fix 2.75 % and 2.4 %). The test holds the visible scene to the
// issue's 2 % at 3e6 photons (docs/validation.md, "Photon map study").
TEST(PhotonMapIntegrator, StudyScenesAgreeWithThePathTracer) {
  for (const StudyScene which : {StudyScene::kLwir, StudyScene::kVisible}) {
    const bool visible = which == StudyScene::kVisible;
    Scene pt = make_study_scene(which, 16, 12, RenderMethod::kPathTracer, 48);
    pt.settings.samples_per_pixel = visible ? 4096 : 1024;
    Scene pm = make_study_scene(which, 16, 12, RenderMethod::kPhotonMap, 48);
    pm.settings.samples_per_pixel = 64;
    pm.settings.photon_map.photons_per_node = visible ? 3000000 : 1000000;
    const SensorImage reference = render_sensor(pt, pt.sensors[0]);
    const SensorImage photon = render_sensor(pm, pm.sensors[0]);
    const double e = testing::systematic_rmse(photon.bands[0], reference.bands[0]);
    EXPECT_LT(e, 0.02) << (visible ? "visible" : "lwir");
  }
}

TEST(PhotonMapIntegrator, ImagesDoNotDependOnTheThreadCount) {
  Scene scene = make_study_scene(StudyScene::kVisible, 12, 8, RenderMethod::kPhotonMap, 32);
  scene.settings.samples_per_pixel = 2;
  scene.settings.photon_map.photons_per_node = 20000;
  const SensorImage a = testing::render_first_sensor(scene, 1);
  const SensorImage b = testing::render_first_sensor(scene, 2);
  EXPECT_EQ(a.stats.photons, b.stats.photons);
  EXPECT_GT(a.stats.photons, 0u);
  EXPECT_EQ(0, std::memcmp(a.bands[0].radiance.data(), b.bands[0].radiance.data(),
                           a.bands[0].radiance.size() * sizeof(float)));
}

}  // namespace
}  // namespace obscura
