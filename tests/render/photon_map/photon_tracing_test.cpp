// Pass 1 of photon mapping: the launched power of every source equals the
// source's power (exactly for the sun and a uniform sky, within the Monte
// Carlo error for a heterogeneous emitting cloud against an independent
// quadrature), photons are stored only where the chosen form says, the
// counts of their walks match closed forms, and the photons do not depend on
// the thread or process count.
#include "obscura/render/photon_map/photon_tracing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "obscura/core/memory_limit.h"
#include "obscura/core/planck.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "support/input_error.h"
#include "support/thread_process_group.h"

namespace obscura {
namespace {

constexpr double kPi = std::numbers::pi;

SpectralNodes nodes_at(double wavelength_um, const std::vector<double>& medium_wl) {
  return SpectralNodes(
      BandQuadrature(Band::flat("mono", wavelength_um - 1e-6, wavelength_um + 1e-6), 1, 0.0),
      medium_wl);
}

Scene cube_scene(double sigma_a, double sigma_s, double temperature) {
  Scene scene;
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({0, 0, 0}, {2, 1, 1}), std::vector<double>{10.0}, std::vector<double>{sigma_a},
      std::vector<double>{sigma_s}, std::vector<double>{0.3}, temperature);
  return scene;
}

TEST(PhotonTracing, LaunchedPowerEqualsTheSourcesPower) {
  Scene scene = cube_scene(0.3, 0.5, 400.0);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 60;
  scene.sky = Sky::blackbody(250.0, true);
  const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
  PhotonTracingSettings s;
  s.photons = 100000;
  const TracedPhotons t = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
  const BoundingSphere sphere = photon_bounding_sphere(scene);
  const double disc = kPi * sphere.radius_m * sphere.radius_m;
  // Sun: E_λ through the disc across the beam.
  EXPECT_NEAR(t.launched.sun_w_um, scene.sun.irradiance(10.0) * disc, 1e-9 * t.launched.sun_w_um);
  // A uniform sky L over the sphere: ∫ L dω × π R² = 4π L π R².
  EXPECT_NEAR(t.launched.environment_w_um, 4 * kPi * planck_radiance(10.0, 250.0) * disc,
              1e-9 * t.launched.environment_w_um);
  // A homogeneous box emits 4π σa B(T) V.
  EXPECT_NEAR(t.launched.emission_w_um, 4 * kPi * 0.3 * planck_radiance(10.0, 400.0) * 2.0,
              1e-9 * t.launched.emission_w_um);
  // Photons are shared out by power.
  const double total = t.launched.total();
  EXPECT_NEAR(t.launched_count[0] / 100000.0, t.launched.sun_w_um / total, 1e-4);
  EXPECT_NEAR(t.launched_count[2] / 100000.0, t.launched.emission_w_um / total, 1e-4);
}

TEST(PhotonTracing, HeterogeneousEmissionIsUnbiased) {
  // A Gaussian puff with a temperature excess: Σ launched powers against a
  // fine midpoint quadrature of ∫ 4π σa B(T) dV over its box.
  GaussianPuffSpec spec;
  spec.radius_m = 1.5;
  spec.extent_radii = 3.0;
  spec.resolution = 40;
  spec.wavelengths_um = {10.0};
  spec.peak_sigma_a = {0.4};
  spec.peak_sigma_s = {0.1};
  spec.g = {0.2};
  spec.ambient_temperature_k = 280;
  spec.temperature_excess_k = 60;
  Scene scene;
  scene.medium =
      std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
  const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
  const SpectralNode& node = nodes.nodes()[0];
  const BBox3 box = scene.medium->bounds();
  const int n = 120;
  const Vec3 h = box.extent() / n;
  double quadrature = 0;
  MediumPoint p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        scene.medium->coefficients_at(
            box.lo + Vec3((i + 0.5) * h.x, (j + 0.5) * h.y, (k + 0.5) * h.z), p);
        quadrature += 4 * kPi * p.sigma_a[0] * node.planck(p.temperature_k);
      }
  quadrature *= h.x * h.y * h.z;
  PhotonTracingSettings s;
  s.photons = 200000;
  const TracedPhotons t = trace_photons(scene, node, 1ull << 40, s);
  EXPECT_EQ(t.launched_count[2], 200000);
  EXPECT_NEAR(t.launched.emission_w_um / quadrature, 1.0, 0.005);
}

// A small emitting cloud in one corner of a large, otherwise empty grid,
// hotter in places: the emission lattice skips the tiles the majorants leave
// empty and must still find all of the cloud. The launched power against a
// fine midpoint quadrature of ∫ 4π σa B(T) dV over the cloud's cells (zero
// elsewhere); with the cloud's tiles skipped it would launch nothing.
TEST(PhotonTracing, AnEmitterInACornerOfAnEmptyGridKeepsItsPower) {
  GridPlacement placement;
  placement.voxel_size_m = 0.25;
  auto grid =
      std::make_shared<VoxelGrid>(GridDims{40, 40, 40}, placement, std::vector<double>{8.0, 12.0});
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        const std::size_t v = grid->index(i, j, k);
        grid->temperature()[v] = 280.0f;
        if (i < 3 || i > 9 || j < 4 || j > 8 || k < 30 || k > 36) continue;
        grid->sigma_a(0)[v] = 0.5f + 0.01f * static_cast<float>(i + 2 * j + 3 * k);
        grid->sigma_a(1)[v] = 0.3f;
        grid->sigma_s(0)[v] = grid->sigma_s(1)[v] = 0.2f;
        grid->temperature()[v] = 300.0f + static_cast<float>(i * j);
      }
  Scene scene;
  scene.medium = std::make_shared<GridMedium>(grid);
  const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
  const SpectralNode& node = nodes.nodes()[0];
  const SpectralLerp lambda = node.lerp();
  // The cloud's reconstruction cells: index coordinates [2, 10] × [3, 9] ×
  // [29, 37], in steps of an eighth of a voxel.
  const double step = 0.25 / 8;
  const Vec3 lo = placement.index_to_world({2, 3, 29});
  double power = 0;
  MediumPoint p;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 64; ++i) {
        scene.medium->coefficients_at(lo + Vec3(i + 0.5, j + 0.5, k + 0.5) * step, p);
        power += 4 * kPi * lambda(p.sigma_a.data()) * node.planck(p.temperature_k);
      }
  power *= step * step * step;
  PhotonTracingSettings s;
  s.photons = 20000;
  const TracedPhotons t = trace_photons(scene, node, 1ull << 40, s);
  EXPECT_EQ(t.launched_count[2], 20000);
  EXPECT_NEAR(t.launched.emission_w_um / power, 1.0, 0.01);
}

TEST(PhotonTracing, StoresScatteringEventsAsTheFormSays) {
  // A non-scattering cloud stores nothing.
  Scene absorbing = cube_scene(0.5, 0.0, 300.0);
  absorbing.sun.enabled = true;
  const SpectralNodes nodes = nodes_at(10.0, absorbing.medium->wavelengths_um());
  PhotonTracingSettings s;
  s.photons = 20000;
  EXPECT_TRUE(trace_photons(absorbing, nodes.nodes()[0], 1ull << 40, s).photons.empty());
  // A thin conservative, cold cloud in sunlight: the pure form stores every
  // scattering, the hybrid form only second and later ones (about τ times
  // fewer).
  Scene thin = cube_scene(0.0, 0.1, 0.0);
  thin.sun.enabled = true;
  const auto hybrid = trace_photons(thin, nodes.nodes()[0], 1ull << 40, s);
  s.store_first_scatter = true;
  const auto pure = trace_photons(thin, nodes.nodes()[0], 1ull << 40, s);
  ASSERT_GT(pure.photons.size(), 300u);
  EXPECT_LT(hybrid.photons.size() * 5, pure.photons.size());
  // Every stored photon lies in the cloud and carries the sun's share of power.
  for (const Photon& ph : pure.photons) {
    EXPECT_TRUE(thin.medium->bounds().contains(ph.position()));
    EXPECT_FLOAT_EQ(ph.power, static_cast<float>(pure.launched.sun_w_um / pure.launched_count[0]));
  }
}

// The photons' walks against closed forms. Sun photons from the zenith
// (a point sun) through the disc of the box's bounding sphere, R² = (2² + 1 +
// 1)/4: a share 2 m² / (π R²) of the lines crosses the box's top, and of
// those 1 − e^{−σt·1 m} collide in it. In a purely absorbing box each photon
// that collides ends there, with one real collision; in a scattering one it
// may collide more. Binomial counts within 4 standard errors.
TEST(PhotonTracing, WalksCountThePhotonsThatMeetTheMedium) {
  for (const double sigma_s : {0.0, 0.6}) {
    Scene scene = cube_scene(0.4, sigma_s, 0.0);
    scene.sun.enabled = true;
    scene.sun.elevation_deg = 90.0;
    scene.sun.angular_diameter_deg = 0.0;
    const SpectralNodes nodes = nodes_at(0.55, scene.medium->wavelengths_um());
    PhotonTracingSettings s;
    s.photons = 200000;
    s.absorb_by_weight = false;
    const TracedPhotons t = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
    ASSERT_EQ(t.launched_count[0], s.photons);  // a black sky and a cold box: the sun alone
    EXPECT_EQ(t.walks.photons, static_cast<std::uint64_t>(s.photons));
    const double disc = kPi * (4.0 + 1.0 + 1.0) / 4.0;
    const double p = 2.0 / disc * (1.0 - std::exp(-(0.4 + sigma_s)));
    const double n = static_cast<double>(s.photons);
    EXPECT_NEAR(static_cast<double>(t.walks.colliding), p * n, 4.0 * std::sqrt(n * p * (1 - p)))
        << "σs " << sigma_s;
    if (sigma_s == 0.0)
      EXPECT_EQ(t.walks.collisions, t.walks.colliding);
    else
      EXPECT_GT(t.walks.collisions, t.walks.colliding + t.walks.colliding / 10);
  }
}

TEST(PhotonTracing, PhotonsDoNotDependOnTheThreadCount) {
  Scene scene = cube_scene(0.2, 1.5, 350.0);
  scene.sun.enabled = true;
  scene.sky = Sky::blackbody(260.0, true);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("g", SurfaceMaterial{290, 0.6}, -0.5));
  const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
  PhotonTracingSettings s;
  s.photons = 30000;
  s.threads = 1;
  const auto a = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
  s.threads = 2;
  const auto b = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
  ASSERT_EQ(a.photons.size(), b.photons.size());
  ASSERT_GT(a.photons.size(), 1000u);
  EXPECT_EQ(0, std::memcmp(a.photons.data(), b.photons.data(), a.photons.size() * sizeof(Photon)));
  EXPECT_EQ(a.launched.environment_w_um, b.launched.environment_w_um);
  EXPECT_EQ(a.walks.colliding, b.walks.colliding);
  EXPECT_EQ(a.walks.collisions, b.walks.collisions);
  // Nor on the process count: every process receives every chunk, its
  // walks' counts too.
  std::vector<TracedPhotons> by_rank(2);
  testing::run_ranks(2, [&](const ProcessGroup& group) {
    PhotonTracingSettings shared = s;
    shared.processes = &group;
    by_rank[static_cast<std::size_t>(group.rank())] =
        trace_photons(scene, nodes.nodes()[0], 1ull << 40, shared);
  });
  for (const TracedPhotons& r : by_rank) {
    ASSERT_EQ(r.photons.size(), a.photons.size());
    EXPECT_EQ(0,
              std::memcmp(r.photons.data(), a.photons.data(), a.photons.size() * sizeof(Photon)));
    EXPECT_EQ(r.walks.photons, a.walks.photons);
    EXPECT_EQ(r.walks.colliding, a.walks.colliding);
    EXPECT_EQ(r.walks.collisions, a.walks.collisions);
  }
}

}  // namespace
}  // namespace obscura

namespace obscura {
namespace {

// A cloud sitting on a black ground: the ground can only absorb what leaves
// the cloud downwards, which escapes anyway without it, so the stored photons
// must be the same, bit for bit. (A regression test: sun photons whose disc
// point lay below the ground were once dropped as "shaded", although their
// line crosses the cloud before it reaches the ground — the photon map then
// saw a cloud on the ground half as bright as the path tracer did.)
TEST(PhotonTracing, ABlackGroundUnderTheCloudChangesNoPhoton) {
  Scene scene = cube_scene(0.05, 1.5, 0.0);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 35.0;
  const SpectralNodes nodes = nodes_at(0.55, scene.medium->wavelengths_um());
  PhotonTracingSettings s;
  s.photons = 20000;
  const auto without = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("g", SurfaceMaterial{0.0, 1.0}, 0.0));
  const auto with = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
  ASSERT_GT(without.photons.size(), 1000u);
  ASSERT_EQ(without.photons.size(), with.photons.size());
  EXPECT_EQ(0, std::memcmp(without.photons.data(), with.photons.data(),
                           with.photons.size() * sizeof(Photon)));
}

// In an enclosure at one temperature (a black ground and the sky at 300 K)
// the radiance is B(T) in every direction everywhere, so the environment
// photons' track lengths through an empty box give its fluence:
// Σ P ℓ_box / V = 4π B(T) (the track-length estimator). With the box lying
// on the ground, many lines whose disc point lies below the ground cross it
// (near-horizontal ones, both the sky's going down and the ground's going
// up): each line's pieces between the surfaces it crosses carry their own
// light. (A regression test: one photon per line from the first surface
// behind the disc point lost those lines' light in the box, and the
// radiance cache's J read 16 % low in such a box; docs/physics.md.) Also
// with a second, raised box as a surface the lines cross inside the
// medium's box. The block is grey (emissivity 0.5; the ground black, so
// that its one reflection sees B(T) everywhere), so what leaves its faces
// is B(T) only when their reflection looks out on the right side: a piece
// after a crossing takes the crossing's surface, its normal turned to face
// the piece.
TEST(PhotonTracing, EnvironmentTracksGiveAnEnclosuresFluence) {
  for (const bool with_block : {false, true}) {
    Scene scene;
    const BBox3 box({-2, -1, 0}, {2, 1, 1});
    scene.medium = std::make_shared<HomogeneousMedium>(
        box, std::vector<double>{10.0}, std::vector<double>{0.0}, std::vector<double>{0.0},
        std::vector<double>{0.0}, 300.0);
    scene.sky = Sky::blackbody(300.0, true);
    scene.surfaces.push_back(std::make_unique<GroundPlane>("g", SurfaceMaterial{300.0, 1.0}, 0.0));
    // A grey block at 300 K inside the medium's box, off the ground: lines
    // through it are cut into pieces before, between and after its faces.
    const BBox3 block({-0.5, -0.5, 0.3}, {0.5, 0.5, 0.6});
    if (with_block)
      scene.surfaces.push_back(
          std::make_unique<BoxSurface>("block", SurfaceMaterial{300.0, 0.5}, block));
    const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
    PhotonTracingSettings s;
    s.photons = 200000;
    s.flights = true;
    s.store_first_environment_scatter = true;
    const TracedPhotons t = trace_photons(scene, nodes.nodes()[0], 1ull << 40, s);
    ASSERT_EQ(t.launched_count[1], s.photons);
    // Per launched line its photons' power × length in the box (the lines
    // are independent; a line's pieces cross disjoint parts of the box).
    double sum = 0.0, sum_sq = 0.0;
    // Inside the block no light travels: no track may cross it (a piece of
    // a line inside a solid launches nothing).
    auto length_in = [](const BBox3& b, const PhotonFlight& f) {
      double t0 = 0.0, t1 = f.length_m;
      const Ray ray{f.origin(), f.dir()};
      return b.intersect(ray, t0, t1) && t1 > t0 ? t1 - t0 : 0.0;
    };
    double in_block = 0.0;
    for (const PhotonFlight& f : t.flights) {
      if (with_block) in_block += f.power * length_in(block, f);
      const double x = f.power * length_in(box, f);
      if (x == 0.0) continue;
      sum += x;
      sum_sq += x * x;
    }
    // (A track from a block's face starts 1e-9 m outside it; its float
    // origin may put a few nanometres inside.)
    EXPECT_LT(in_block, 1e-6 * sum) << "with the block: " << with_block;
    const double n = static_cast<double>(s.photons);
    const double volume = 8.0 - (with_block ? 0.3 : 0.0);
    const double fluence = sum / volume;
    const double stderr_fluence = std::sqrt(std::max(0.0, sum_sq - sum * sum / n)) / volume;
    const double expected = 4 * kPi * planck_radiance(10.0, 300.0);
    // Within 4 standard errors (about 0.6 %) and 1.5 %; the lost lines took
    // about 25 % of it.
    EXPECT_NEAR(fluence, expected, std::min(4.0 * stderr_fluence, 0.015 * expected))
        << "with the block: " << with_block << ", standard error " << stderr_fluence / expected;
  }
}

}  // namespace
}  // namespace obscura

namespace obscura {
namespace {

// Photons stored past the memory limit stop the tracing with an error naming
// the setting, on every process alike (two ranks as threads here: neither
// waits for the other in a collective), and the limit restored lets the
// same tracing through.
TEST(PhotonTracing, StoringPastTheMemoryLimitIsAnErrorOnEveryProcess) {
  Scene scene = cube_scene(0.01, 20.0, 300.0);  // many scatterings per photon
  scene.sun.enabled = true;
  const SpectralNodes nodes = nodes_at(10.0, scene.medium->wavelengths_um());
  PhotonTracingSettings s;
  s.photons = 20000;
  s.threads = 2;
  s.memory_field = "render/radiance_cache/photons";
  set_memory_limit(256 * 1024, MemoryLimitSource::kCommandLine);
  const InputError e =
      testing::expect_input_error([&] { trace_photons(scene, nodes.nodes()[0], 0, s); });
  EXPECT_EQ(e.field(), "render/radiance_cache/photons");
  EXPECT_NE(std::string(e.detail()).find("outgrew the memory limit"), std::string::npos)
      << e.what();
  std::vector<std::string> messages(2);
  testing::run_ranks(2, [&](const ProcessGroup& group) {
    PhotonTracingSettings shared = s;
    shared.processes = &group;
    try {
      trace_photons(scene, nodes.nodes()[0], 0, shared);
    } catch (const InputError& error) {
      messages[static_cast<std::size_t>(group.rank())] = error.what();
    }
  });
  EXPECT_NE(messages[0].find("outgrew the memory limit"), std::string::npos) << messages[0];
  EXPECT_EQ(messages[0], messages[1]);
  reset_memory_limit();
  const TracedPhotons traced = trace_photons(scene, nodes.nodes()[0], 0, s);
  EXPECT_GT(traced.photons.size() * sizeof(Photon), 256u * 1024u);
}

}  // namespace
}  // namespace obscura
