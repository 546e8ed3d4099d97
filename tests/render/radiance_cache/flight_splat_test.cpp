// The track-length splat (render/radiance_cache/flight_splat.h): a flight
// adds to each node ΔΦ Y_lm ∫ K σs dt, checked against a brute-force
// quadrature along the flight on a random rotated grid; the result does not
// depend on the thread count; and on the same photon walks its total equals
// the collision estimate's within the statistical error.
#include "obscura/render/radiance_cache/flight_splat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "medium/test_grids.h"
#include "obscura/core/sampling.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/photon_map/photon_tracing.h"
#include "obscura/render/radiance_cache/cache_source.h"
#include "obscura/render/radiance_cache/spherical_harmonics.h"
#include "support/thread_process_group.h"

namespace obscura {
namespace {

// The grids' shapes: longest along z, x and y in turn, so that the slabs the
// splat is cut into (along the lattice's longest axis) lie across each axis.
const GridDims kShapes[] = {{9, 7, 22}, {26, 7, 9}, {8, 24, 6}};

// A random rotated grid; with `g`, one asymmetry everywhere (a cloud of one
// material) instead of a random one per voxel.
std::shared_ptr<VoxelGrid> fixture_grid(const GridDims& dims, std::optional<float> g) {
  auto grid = testing::random_grid(dims, 2, 21, rotation_from_euler_deg({15, -25, 40}));
  if (g)
    for (int s = 0; s < 2; ++s)
      for (std::size_t v = 0; v < grid->dims().count(); ++v) grid->g(s)[v] = *g;
  return grid;
}

struct Fixture {
  explicit Fixture(const GridDims& dims = kShapes[0], std::optional<float> g = std::nullopt)
      : grid(fixture_grid(dims, g)) {}
  std::shared_ptr<VoxelGrid> grid;
  GridMedium medium{grid};
  NodeLattice lattice{medium, 0.0, 0.0, 1u << 30};
  SpectralLerp lerp{0, 1, 0.3};
  LatticeVolume volume{lattice, {lerp}, record::light_stride(9), grid.get(), 1, "test"};
};

// Calls visit(x, σs(x), dt) at the midpoints of `steps` equal steps along
// the flight where the medium scatters.
template <class Visit>
void for_each_step(const Fixture& f, const PhotonFlight& flight, int steps, Visit&& visit) {
  const double dt = flight.length_m / steps;
  MediumPoint point;
  for (int i = 0; i < steps; ++i) {
    const Vec3 x = flight.origin() + flight.dir() * ((i + 0.5) * dt);
    f.medium.coefficients_at(x, point);
    const double sigma_s = f.lerp(point.sigma_s.data());
    if (sigma_s != 0.0) visit(x, sigma_s, dt);
  }
}

// ∫ hat_n(u(t)) σs(u(t)) dt / h³ along a flight by the midpoint rule with
// many steps, σs from the medium itself; with `view`, the same weighted by
// the phase function's part beyond degree 2 towards it (hg_beyond_degree,
// with g = (σs g)/σs of the records' trilinear σs g and σs, as the cache
// reads it everywhere: the peak is steep in g).
std::vector<double> brute_force(const Fixture& f, const PhotonFlight& flight,
                                const Vec3* view = nullptr) {
  const NodeLattice& lattice = f.lattice;
  std::vector<double> out(lattice.slot_count(), 0.0);
  const double h = lattice.spacing_m();
  for_each_step(f, flight, 200000, [&](const Vec3& x, double sigma_s, double dt) {
    std::array<std::size_t, 8> slot;
    std::array<double, 8> w;
    if (!lattice.corners(x, slot, w)) return;
    double weight = 1.0;
    if (view) {
      double sg = 0.0, s = 0.0;
      for (int c = 0; c < 8; ++c) {
        if (slot[c] == NodeLattice::kNoSlot) continue;
        const float* r = f.volume.records(0) + slot[c] * f.volume.stride();
        sg += w[c] * r[record::kSigmaSG];
        s += w[c] * r[record::kSigmaS];
      }
      weight = hg_beyond_degree(cache_clamped_g(sg / s), dot(flight.dir(), *view), 2);
    }
    for (int c = 0; c < 8; ++c)
      if (slot[c] != NodeLattice::kNoSlot)
        out[slot[c]] += w[c] * sigma_s * weight * dt / (h * h * h);
  });
  return out;
}

// The index of the lattice's longest axis.
int longest_axis(const NodeLattice& lattice) {
  const std::array<int, 3>& d = lattice.dims();
  return static_cast<int>(std::max_element(d.begin(), d.end()) - d.begin());
}

TEST(FlightSplat, TheShapesCutTheSlabsAcrossEachAxis) {
  // What the tests below rely on: slabs of 8 node layers along each axis in
  // turn, at least three of them.
  for (int a = 0; a < 3; ++a) {
    const Fixture f(kShapes[a]);
    EXPECT_EQ(longest_axis(f.lattice), (a + 2) % 3) << "shape " << a;
    const std::array<int, 3>& d = f.lattice.dims();
    EXPECT_GT(d[static_cast<std::size_t>(longest_axis(f.lattice))], 16)
        << "shape " << a << ": " << d[0] << " x " << d[1] << " x " << d[2] << " nodes";
  }
}

class FlightSplatShapes : public ::testing::TestWithParam<int> {};

TEST_P(FlightSplatShapes, EachNodeGetsTheKernelIntegralAlongTheFlight) {
  const GridDims& shape = kShapes[GetParam()];
  const Fixture f(shape);
  const BBox3 box = f.medium.bounds();
  Rng rng(4, 0);
  for (int n = 0; n < 6; ++n) {
    // A flight through the grid, starting outside or inside, ending inside or beyond.
    const Vec3 e = box.extent();
    const GridDims& n3 = f.grid->dims();
    const Vec3 target = f.grid->placement().index_to_world(Vec3(
        (n3.nx - 1) * rng.uniform(), (n3.ny - 1) * rng.uniform(), (n3.nz - 1) * rng.uniform()));
    const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    // From inside, ending inside or beyond; from outside, right through.
    const Vec3 start = n % 2 ? target : target - d * length(e);
    const double len = n % 2 ? (n % 3 ? 0.3 : 2.0) * length(e) : 2.0 * length(e);
    const PhotonFlight flight{
        {static_cast<float>(start.x), static_cast<float>(start.y), static_cast<float>(start.z)},
        {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)},
        static_cast<float>(len),
        2.5f};
    std::vector<double> sum(f.lattice.slot_count() * 9, 0.0);
    splat_flights(f.volume, 0, {flight}, 2, 2, sum);
    const std::vector<double> exact = brute_force(f, flight);
    std::array<double, kMaxShCoefficients> y;
    spherical_harmonics(flight.dir(), y, 2);
    double largest = 0.0;
    for (const double v : exact) largest = std::max(largest, v);
    ASSERT_GT(largest, 0.0);
    for (std::size_t slot = 0; slot < f.lattice.slot_count(); ++slot)
      for (int l = 0; l < 9; ++l)
        ASSERT_NEAR(sum[slot * 9 + l], 2.5 * y[l] * exact[slot], 2e-3 * 2.5 * largest)
            << "flight " << n << " slot " << slot << " coefficient " << l;
    // At degree 6 (49 harmonics: twelve groups of four and one more) each
    // harmonic of the flight's direction takes the same integral.
    std::vector<double> sum_6(f.lattice.slot_count() * 49, 0.0);
    splat_flights(f.volume, 0, {flight}, 6, 2, sum_6);
    spherical_harmonics(flight.dir(), y, 6);
    for (std::size_t slot = 0; slot < f.lattice.slot_count(); ++slot)
      for (int l = 0; l < 49; ++l)
        ASSERT_NEAR(sum_6[slot * 49 + l], 2.5 * y[l] * exact[slot], 2e-3 * 2.5 * largest)
            << "degree 6, flight " << n << " slot " << slot << " coefficient " << l;
    // With two sensors' directions, one near the flight's (the forward
    // peak) and one across it: two more sums per slot, the harmonics' the
    // same. On a grid of one g (q then constant along the flight; with g
    // random per voxel, the three Gauss points per cell follow q, steep in
    // g near the peak, only to a few per cent).
    const std::vector<Vec3> views = {normalize(flight.dir() + Vec3(0.05, -0.03, 0.02)),
                                     normalize(cross(flight.dir(), Vec3(0.3, 0.5, 0.8)))};
    const Fixture one_g(shape, 0.7f);
    std::vector<double> plain(f.lattice.slot_count() * 9, 0.0),
        with_peaks(f.lattice.slot_count() * 11, 0.0);
    splat_flights(one_g.volume, 0, {flight}, 2, 2, plain);
    splat_flights(one_g.volume, 0, {flight}, 2, 2, with_peaks, single_process(), views);
    for (int v = 0; v < 2; ++v) {
      const std::vector<double> peak = brute_force(one_g, flight, &views[v]);
      double peak_largest = 0.0;
      for (const double p : peak) peak_largest = std::max(peak_largest, std::abs(p));
      ASSERT_GT(peak_largest, 0.0);
      for (std::size_t slot = 0; slot < f.lattice.slot_count(); ++slot) {
        for (int l = 0; l < 9; ++l)
          ASSERT_EQ(with_peaks[slot * 11 + l], plain[slot * 9 + l]) << "slot " << slot;
        ASSERT_NEAR(with_peaks[slot * 11 + 9 + v], 2.5 * peak[slot], 2e-3 * 2.5 * peak_largest)
            << "flight " << n << " slot " << slot << " view " << v;
      }
    }
  }
}

// 3000 flights from random points of the grid's box in random directions,
// up to 3 m long.
std::vector<PhotonFlight> random_flights(const Fixture& f, std::uint64_t seed) {
  std::vector<PhotonFlight> flights;
  Rng rng(seed, 0);
  const BBox3 box = f.medium.bounds();
  for (int i = 0; i < 3000; ++i) {
    const Vec3 e = box.extent();
    const Vec3 p = box.lo + Vec3(e.x * rng.uniform(), e.y * rng.uniform(), e.z * rng.uniform());
    const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    flights.push_back({{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)},
                       {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)},
                       static_cast<float>(3.0 * rng.uniform()),
                       static_cast<float>(rng.uniform())});
  }
  return flights;
}

TEST_P(FlightSplatShapes, TheSumsDoNotDependOnTheThreadOrProcessCount) {
  const Fixture f(kShapes[GetParam()]);
  const std::vector<PhotonFlight> flights = random_flights(f, 8);
  // Degree 3 and two sensors' peaks: 18 sums per slot.
  const std::vector<Vec3> views = {normalize(Vec3(0.2, -1.0, 0.1)), Vec3(0, 0, 1)};
  std::vector<double> one(f.lattice.slot_count() * 18, 0.0), two = one;
  splat_flights(f.volume, 0, flights, 3, 1, one, single_process(), views);
  splat_flights(f.volume, 0, flights, 3, 2, two, single_process(), views);
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(double)));
  EXPECT_GT(std::count_if(one.begin(), one.end(), [](double v) { return v != 0.0; }), 1000);
  // Ranks share the slabs and exchange their sums: every rank ends with the
  // bits of one process (at least 3 slabs, dealt unevenly).
  for (const int ranks : {2, 3, 5}) {
    std::vector<std::vector<double>> by_rank(static_cast<std::size_t>(ranks));
    testing::run_ranks(ranks, [&](const ProcessGroup& processes) {
      std::vector<double> sum(one.size(), 0.0);
      splat_flights(f.volume, 0, flights, 3, 1, sum, processes, views);
      by_rank[static_cast<std::size_t>(processes.rank())] = std::move(sum);
    });
    for (int r = 0; r < ranks; ++r)
      EXPECT_EQ(0, std::memcmp(one.data(), by_rank[static_cast<std::size_t>(r)].data(),
                               one.size() * sizeof(double)))
          << ranks << " ranks, rank " << r;
  }
}

// With a box of cells (light_region.h) the walk is cut to it, each cell
// keeping the crossings of the whole walk: a node whose eight cells are all
// in the box gets the same bits as without it, nodes outside get nothing,
// and nodes on its faces part of their sums.
TEST_P(FlightSplatShapes, ABoxOfCellsKeepsTheSumsOfTheNodesInside) {
  const Fixture f(kShapes[GetParam()]);
  const std::vector<PhotonFlight> flights = random_flights(f, 9);
  const std::vector<Vec3> views = {normalize(Vec3(0.2, -1.0, 0.1))};
  const std::size_t per_slot = 17;  // degree 3 and one sensor's peak
  std::vector<double> whole(f.lattice.slot_count() * per_slot, 0.0), cut = whole;
  splat_flights(f.volume, 0, flights, 3, 2, whole, single_process(), views);
  // The middle of the lattice, a third to two thirds along each axis.
  CellBox box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = f.lattice.dims()[a] / 3;
    box.hi[a] = 2 * f.lattice.dims()[a] / 3;
  }
  splat_flights(f.volume, 0, flights, 3, 2, cut, single_process(), views, &box);
  int inside = 0, on_faces = 0, faces_differ = 0;
  for (std::size_t slot = 0; slot < f.lattice.slot_count(); ++slot) {
    if (!f.lattice.slot_inside(slot)) continue;
    const std::array<int, 3> n = f.lattice.slot_node(slot);
    bool core = true, reached = true;
    for (int a = 0; a < 3; ++a) {
      core = core && n[a] >= box.lo[a] + 1 && n[a] <= box.hi[a];
      reached = reached && n[a] >= box.lo[a] && n[a] <= box.hi[a] + 1;
    }
    const double* w = whole.data() + slot * per_slot;
    const double* c = cut.data() + slot * per_slot;
    if (core) {
      ++inside;
      EXPECT_EQ(0, std::memcmp(w, c, per_slot * sizeof(double)))
          << "node " << n[0] << " " << n[1] << " " << n[2];
    } else if (reached) {
      ++on_faces;
      faces_differ += std::memcmp(w, c, per_slot * sizeof(double)) != 0;
    } else {
      for (std::size_t k = 0; k < per_slot; ++k) EXPECT_EQ(c[k], 0.0);
    }
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(faces_differ, on_faces / 4);
}

INSTANTIATE_TEST_SUITE_P(LongestAxis, FlightSplatShapes, ::testing::Values(0, 1, 2));

// ∫ K_r(u(t) − n) σs(u(t)) dt along a flight for the tent of r spacings,
// K_r(u) = Π_a max(0, 1 − |u_a|/r) / (r h)³, by the midpoint rule with many
// steps: what widen_splat must make of the one-spacing sums.
std::vector<double> brute_force_wide(const Fixture& f, const PhotonFlight& flight, int r) {
  const NodeLattice& lattice = f.lattice;
  std::vector<double> out(lattice.slot_count(), 0.0);
  const double rh = r * lattice.spacing_m();
  for_each_step(f, flight, 100000, [&](const Vec3& x, double sigma_s, double dt) {
    const Vec3 u = lattice.to_lattice(x);
    const int i0 = static_cast<int>(std::floor(u.x)), j0 = static_cast<int>(std::floor(u.y)),
              k0 = static_cast<int>(std::floor(u.z));
    for (int k = k0 - r + 1; k <= k0 + r; ++k)
      for (int j = j0 - r + 1; j <= j0 + r; ++j)
        for (int n = i0 - r + 1; n <= i0 + r; ++n) {
          const std::size_t slot = lattice.slot_of(n, j, k);
          if (slot == NodeLattice::kNoSlot) continue;
          const double w = std::max(0.0, 1.0 - std::abs(u.x - n) / r) *
                           std::max(0.0, 1.0 - std::abs(u.y - j) / r) *
                           std::max(0.0, 1.0 - std::abs(u.z - k) / r);
          out[slot] += w * sigma_s * dt / (rh * rh * rh);
        }
  });
  return out;
}

TEST(FlightSplat, WideningGivesTheWideTentsIntegralAlongTheFlight) {
  const Fixture f(kShapes[1]);
  const BBox3 box = f.medium.bounds();
  Rng rng(11, 0);
  for (const int r : {2, 3}) {
    for (int n = 0; n < 3; ++n) {
      const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
      const Vec3 target = box.center() + Vec3(0.2 * rng.uniform(), -0.1 * rng.uniform(), 0.0) *
                                             length(box.extent());
      const Vec3 start = target - d * length(box.extent());
      const PhotonFlight flight{
          {static_cast<float>(start.x), static_cast<float>(start.y), static_cast<float>(start.z)},
          {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)},
          static_cast<float>(2.0 * length(box.extent())),
          1.5f};
      std::vector<double> one(f.lattice.slot_count() * 9, 0.0);
      splat_flights(f.volume, 0, {flight}, 2, 2, one);
      std::vector<double> wide = one, wide_threads = one;
      widen_splat(f.lattice, r, 9, 1, wide);
      widen_splat(f.lattice, r, 9, 2, wide_threads);
      EXPECT_EQ(0, std::memcmp(wide.data(), wide_threads.data(), wide.size() * sizeof(double)));
      const std::vector<double> exact = brute_force_wide(f, flight, r);
      std::array<double, kMaxShCoefficients> y;
      spherical_harmonics(flight.dir(), y, 2);
      double largest = 0.0;
      for (const double v : exact) largest = std::max(largest, v);
      ASSERT_GT(largest, 0.0);
      // The widened sums reach nodes the one-spacing splat did not.
      std::size_t reached_one = 0, reached_wide = 0;
      for (std::size_t slot = 0; slot < f.lattice.slot_count(); ++slot) {
        reached_one += one[slot * 9] != 0.0;
        reached_wide += wide[slot * 9] != 0.0;
        for (int l = 0; l < 9; ++l)
          ASSERT_NEAR(wide[slot * 9 + l], 1.5 * y[l] * exact[slot], 2e-3 * 1.5 * largest)
              << "r " << r << " flight " << n << " slot " << slot << " coefficient " << l;
      }
      EXPECT_GT(reached_wide, reached_one);
    }
  }
  // r = 1 changes nothing.
  std::vector<double> sum(f.lattice.slot_count(), 0.5), same = sum;
  widen_splat(f.lattice, 1, 1, 2, same);
  EXPECT_EQ(sum, same);
}

// On the same walks (flights do not change the random numbers drawn), the
// total scattered power by tracks, Σ ΔΦ ∫ σs dt, equals the collisions',
// Σ ΔΦ: both estimate ∫∫ σs L dV dω.
TEST(FlightSplat, TracksAndCollisionsEstimateTheSameScatteredPower) {
  Scene scene;
  auto grid = testing::random_grid({12, 10, 8}, 2, 5);
  for (int s = 0; s < 2; ++s)  // thinner, so that photons cross several cells
    for (std::size_t v = 0; v < grid->dims().count(); ++v) {
      grid->sigma_a(s)[v] *= 0.1f;
      grid->sigma_s(s)[v] *= 0.5f;
    }
  scene.medium = std::make_shared<GridMedium>(grid);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 50;
  scene.sky = Sky::blackbody(260, false);
  const SpectralNodes nodes(BandQuadrature(Band::flat("b", 3.2, 3.4), 1, 0.0),
                            grid->wavelengths_um());
  const SpectralNode& node = nodes.nodes()[0];
  PhotonTracingSettings settings;
  settings.photons = 200000;
  settings.store_first_environment_scatter = true;
  settings.threads = 2;
  const TracedPhotons collisions = trace_photons(scene, node, 0, settings);
  settings.flights = true;
  const TracedPhotons tracks = trace_photons(scene, node, 0, settings);
  ASSERT_TRUE(tracks.photons.empty());
  ASSERT_GT(tracks.flights.size(), collisions.photons.size());
  double by_collisions = 0.0, by_tracks = 0.0, power2 = 0.0;
  for (const Photon& p : collisions.photons) {
    by_collisions += p.power;
    power2 += static_cast<double>(p.power) * p.power;
  }
  const NodeLattice lattice(*scene.medium, 0.0, 0.0, 1u << 30);
  const LatticeVolume volume(lattice, {node.lerp()}, record::light_stride(1), grid.get(), 1, "t");
  std::vector<double> sum(lattice.slot_count(), 0.0);
  splat_flights(volume, 0, tracks.flights, 0, 2, sum);
  const double h = lattice.spacing_m();
  for (const double v : sum) by_tracks += v;
  by_tracks *= h * h * h / 0.28209479177387814;  // undo Y_00 and the kernel's 1/h³
  // The collisions' total is a sum of ~N independent-ish weights: its
  // standard error is about √Σ ΔΦ².
  EXPECT_NEAR(by_tracks, by_collisions, 4.0 * std::sqrt(power2) + 1e-3 * by_collisions);
  EXPECT_GT(by_collisions, 0.0);
}

}  // namespace
}  // namespace obscura
