// The march's items (gpu/march_job.h) on the CPU's threads (gpu/host_executor.h)
// against the CPU's own march of every node of a band along one ray
// (render/lattice/lattice_march.h, render/radiance_cache/cache_march.h): the
// same arithmetic per node, so the same bits, for emission–absorption and
// the radiance cache at every degree, rays from outside and inside, stopping
// on a surface, and nodes between the grid's spectral samples.
#include "obscura/gpu/march_job.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "medium/test_grids.h"
#include "obscura/core/sampling.h"
#include "obscura/gpu/host_executor.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/lattice/lattice_march.h"
#include "obscura/render/radiance_cache/cache_march.h"
#include "support/frame_lattice.h"
#include "support/sunlit_grid.h"

namespace obscura {
namespace {

// Rays through and around `box`: from outside, from inside, some ending part-way.
std::vector<CameraRay> rays_around(const BBox3& box, int count, std::uint64_t seed) {
  Rng rng(seed, 0);
  std::vector<CameraRay> rays;
  const Vec3 c = box.center(), e = box.extent();
  for (int i = 0; i < count; ++i) {
    const Vec3 inside(box.lo.x + e.x * rng.uniform(), box.lo.y + e.y * rng.uniform(),
                      box.lo.z + e.z * rng.uniform());
    const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    CameraRay camera;
    camera.ray = Ray{i % 3 == 0 ? inside : c - d * (2.0 * length(e)) + (inside - c) * 0.5, d};
    if (i % 4 == 0) {
      camera.on_surface = true;
      camera.hit.t = length(e) * rng.uniform();
    }
    rays.push_back(camera);
  }
  return rays;
}

std::vector<MarchRay> march_rays(const std::vector<CameraRay>& rays) {
  std::vector<MarchRay> out;
  for (const CameraRay& r : rays) out.push_back({r.ray.origin, r.ray.direction, r.t_end()});
  return out;
}

TEST(MarchJob, EmissionItemsEqualTheCpuMarchBitForBit) {
  const auto grid =
      testing::random_grid({19, 13, 22}, 3, 21, rotation_from_euler_deg({20, -35, 70}));
  const GridMedium medium(grid);
  // Two bands whose nodes lie between the grid's samples.
  const SpectralNodes band0(BandQuadrature(Band::flat("a", 3.1, 4.8), 3, 0.0),
                            grid->wavelengths_um());
  const SpectralNodes band1(BandQuadrature(Band::flat("b", 4.1, 4.9), 2, 0.0),
                            grid->wavelengths_um());
  std::vector<SpectralNode> nodes(band0.nodes());
  nodes.insert(nodes.end(), band1.nodes().begin(), band1.nodes().end());
  std::vector<SpectralLerp> lerps;
  for (const SpectralNode& nd : nodes) lerps.push_back(nd.lerp());
  const GridRecords records = grid_records(medium, lerps, record::kMediumStride, 2);
  ASSERT_TRUE(records.volume);
  HostExecutor executor(3);
  executor.load(testing::frame_of(*records.volume, nodes, nullptr));
  MarchRequest request;
  request.output_node = {0, 1, 2, 3, 4};
  const std::vector<CameraRay> rays = rays_around(medium.bounds(), 500, 4);
  MarchResult result;
  executor.march(request, march_rays(rays), result);
  ASSERT_EQ(result.radiance.size(), 5 * rays.size());

  std::array<PlanckTableView, 5> planck;
  for (int u = 0; u < 5; ++u) planck[u] = nodes[u].planck_table->view();
  int crossing = 0;
  for (std::size_t i = 0; i < rays.size(); ++i)
    for (const auto& [first, n] : {std::pair{0, 3}, std::pair{3, 2}}) {
      const int record[3] = {first, first + 1, first + 2};
      double l[3] = {0, 0, 0}, t[3] = {1, 1, 1};
      const std::uint64_t cells = march_lattice<record::kMediumStride>(
          *records.volume, record, n, rays[i].ray, rays[i].t_end(),
          EmissionSource{planck.data() + first}, l, t);
      crossing += cells > 0 && first == 0;
      for (int j = 0; j < n; ++j) {
        const std::size_t at = static_cast<std::size_t>(first + j) * rays.size() + i;
        ASSERT_EQ(result.radiance[at], l[j]) << "ray " << i << " node " << first + j;
        ASSERT_EQ(result.transmittance[at], t[j]) << "ray " << i << " node " << first + j;
        ASSERT_EQ(result.cells[at], cells) << "ray " << i;
      }
    }
  EXPECT_GT(crossing, 250);
}

TEST(MarchJob, CacheItemsEqualTheCpuMarchBitForBitAtEveryDegree) {
  for (const int degree : {0, 1, 2, 3}) {
    Scene scene = testing::sunlit_grid_scene(degree);
    // A narrow sensor, so that the cache holds a forward peak towards it and
    // both marches read it.
    const Vec3 centre = scene.medium->bounds().center();
    Sensor narrow;
    narrow.name = "narrow";
    narrow.camera = PinholeCamera(centre + Vec3(5, -60, 8), centre, {0, 0, 1}, 3.0, 8, 8);
    scene.sensors.push_back(narrow);
    const SpectralNodes band(BandQuadrature(Band::flat("b", 3.2, 4.9), 3, 0.0),
                             scene.medium->wavelengths_um());
    const std::vector<SpectralNode> nodes(band.nodes());
    const RadianceCache cache(scene, nodes);
    ASSERT_TRUE(cache.volume().has_medium());
    ASSERT_GE(cache.peak_channel(0), 0) << "degree " << degree;
    HostExecutor executor(2);
    executor.load(testing::frame_of(cache.volume(), nodes, &scene));
    MarchRequest request;
    request.source = MarchSource::kCache;
    request.sh_degree = degree;
    request.sun = true;
    request.to_sun = scene.sun.direction();
    request.output_node = {0, 1, 2};
    const std::vector<CameraRay> rays = rays_around(scene.medium->bounds(), 200, 5 + degree);
    // With the narrow sensor's peak, and without one (delta-M: the
    // attenuation then differs from the transmittance).
    for (const int peak : {cache.peak_channel(0), -1}) {
      request.peak_channel = peak;
      MarchResult result;
      executor.march(request, march_rays(rays), result);
      const int record[3] = {0, 1, 2};
      int lit = 0, forward = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        double l[3] = {0, 0, 0}, t[3] = {1, 1, 1}, a[3] = {1, 1, 1};
        const std::uint64_t cells =
            march_cache_lattice(scene, cache, rays[i], band, record, peak, l, t, a);
        lit += l[0] > 0;
        forward += a[0] != t[0];
        for (std::size_t j = 0; j < 3; ++j) {
          ASSERT_EQ(result.radiance[j * rays.size() + i], l[j])
              << "degree " << degree << " peak " << peak << " ray " << i;
          ASSERT_EQ(result.transmittance[j * rays.size() + i], t[j]);
          ASSERT_EQ(result.attenuation[j * rays.size() + i], a[j]);
          ASSERT_EQ(result.cells[j * rays.size() + i], cells);
        }
      }
      EXPECT_GT(lit, 60) << "degree " << degree << " peak " << peak;
      if (peak >= 0)
        EXPECT_EQ(forward, 0) << "degree " << degree;
      else
        EXPECT_GT(forward, 60) << "degree " << degree;
    }
  }
}

TEST(MarchJob, RecordLengthsMatchTheirKernels) {
  EXPECT_EQ(sh_degree_of_stride(8), 0);
  EXPECT_EQ(sh_degree_of_stride(12), 1);
  EXPECT_EQ(sh_degree_of_stride(16), 2);
  EXPECT_EQ(sh_degree_of_stride(24), 3);
  // The CPU's degrees 4–6 have no device kernels.
  for (const int count : {25, 36, 49})
    EXPECT_EQ(sh_degree_of_stride(record::light_stride(count)), -1);
  EXPECT_EQ(sh_degree_of_stride(record::kMediumStride), -1);
  EXPECT_EQ(sh_degree_of_stride(20), -1);
  EXPECT_TRUE(march_supported(record::kMediumStride, MarchSource::kEmission));
  EXPECT_FALSE(march_supported(16, MarchSource::kEmission));
  EXPECT_FALSE(march_supported(record::kMediumStride, MarchSource::kCache));
  for (const int degree : {0, 1, 2, 3}) {
    const int stride = record::light_stride(sh_coefficient_count(degree));
    EXPECT_TRUE(march_supported(stride, MarchSource::kCache));
    int seen = -1;
    MarchJob job;
    job.source = MarchSource::kCache;
    job.stride = stride;
    dispatch_march(job, [&](auto s, auto kind) {
      seen = decltype(s)::value;
      EXPECT_EQ(decltype(kind)::value, MarchSource::kCache);
    });
    EXPECT_EQ(seen, stride);
  }
}

TEST(MarchJob, AJobTheKernelsCannotRunIsRefused) {
  LatticeView view;
  MarchRequest request;
  request.output_node = {0, 1};
  EXPECT_NO_THROW(make_march_job(view, record::kMediumStride, 2, request, 10));
  EXPECT_EQ(make_march_job(view, record::kMediumStride, 2, request, 10).items(), 20u);
  EXPECT_THROW(make_march_job(view, 16, 2, request, 10), std::invalid_argument);  // medium only
  request.output_node = {0, 2};
  EXPECT_THROW(make_march_job(view, record::kMediumStride, 2, request, 10), std::invalid_argument);
  request.output_node = {0};
  request.source = MarchSource::kCache;
  request.sh_degree = 1;
  EXPECT_THROW(make_march_job(view, 16, 1, request, 10), std::invalid_argument);  // degree 2's
  request.sh_degree = 2;
  EXPECT_NO_THROW(make_march_job(view, 16, 1, request, 10));
}

}  // namespace
}  // namespace obscura
