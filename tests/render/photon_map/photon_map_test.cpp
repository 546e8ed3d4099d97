#include "obscura/render/photon_map/photon_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/rng.h"

// The photon map is checked against brute force: every query's index sequence
// and distances must be identical, including the documented tie-break by index
// (which nanoflann's own result sets do not give: they drop a photon that ties
// the current k-th distance and exclude photons exactly on the radius).

namespace obscura {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Photon photon_at(double x, double y, double z, float power = 1.0f) {
  return Photon{{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)},
                {0.0f, 0.0f, 1.0f},
                power};
}

std::vector<Photon> uniform_box(int n, std::uint64_t seed) {
  Rng rng(seed, 0);
  std::vector<Photon> v;
  for (int i = 0; i < n; ++i)
    v.push_back(photon_at(-5 + 10 * rng.uniform(), -2 + 4 * rng.uniform(), 30 * rng.uniform()));
  return v;
}

// Gaussian blobs of very different widths, so the tree is deep in the tight
// blob and shallow in the wide one.
std::vector<Photon> gaussian_blobs(int n, std::uint64_t seed) {
  Rng rng(seed, 0);
  const Vec3 centres[3] = {{0, 0, 0}, {20, 5, -3}, {-7, 12, 40}};
  const double sigmas[3] = {0.01, 1.0, 5.0};
  std::vector<Photon> v;
  for (int i = 0; i < n; ++i) {
    const int b = i % 3;
    Vec3 g;
    for (int a = 0; a < 3; ++a) {  // Box–Muller
      const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();
      g[a] = std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
    }
    const Vec3 x = centres[b] + g * sigmas[b];
    v.push_back(photon_at(x.x, x.y, x.z));
  }
  return v;
}

// Integer lattice points {0..4}³ drawn at random: many exact duplicates, and
// from a lattice query point many photons at exactly equal distances.
std::vector<Photon> lattice_duplicates(int n, std::uint64_t seed) {
  Rng rng(seed, 0);
  std::vector<Photon> v;
  auto pick = [&] { return std::floor(5 * rng.uniform()); };
  for (int i = 0; i < n; ++i) v.push_back(photon_at(pick(), pick(), pick()));
  return v;
}

// Every photon on the plane z = 2.5 (a zero-width box axis).
std::vector<Photon> plane(int n, std::uint64_t seed) {
  Rng rng(seed, 0);
  std::vector<Photon> v;
  for (int i = 0; i < n; ++i) v.push_back(photon_at(10 * rng.uniform(), 10 * rng.uniform(), 2.5));
  return v;
}

// Query points: random ones over (and a little beyond) the photons' box,
// every lattice point of {-1..5}³ stepped by 1 (exact ties for the lattice
// set), some photon positions themselves (distance 0) and far-away points.
std::vector<Vec3> query_points(const std::vector<Photon>& photons, std::uint64_t seed) {
  std::vector<Vec3> q;
  Vec3 lo{-1, -1, -1}, hi{1, 1, 1};
  if (!photons.empty()) {
    lo = hi = photons[0].position();
    for (const Photon& p : photons) {
      lo = component_min(lo, p.position());
      hi = component_max(hi, p.position());
    }
  }
  const Vec3 pad = (hi - lo) * 0.1 + Vec3{0.1, 0.1, 0.1};
  lo -= pad;
  hi += pad;
  Rng rng(seed, 1);
  for (int i = 0; i < 60; ++i)
    q.push_back({lo.x + (hi.x - lo.x) * rng.uniform(), lo.y + (hi.y - lo.y) * rng.uniform(),
                 lo.z + (hi.z - lo.z) * rng.uniform()});
  for (int x = -1; x <= 5; x += 2)
    for (int y = -1; y <= 5; y += 2)
      for (int z = -1; z <= 5; z += 2) q.push_back({double(x), double(y), double(z)});
  for (std::size_t i = 0; i < photons.size() && i < 200; i += 37)
    q.push_back(photons[i].position());
  q.push_back({1e4, -3e3, 7e3});
  q.push_back({-50, 0, 0});
  return q;
}

// The reference: all photons within r, sorted by (distance², index), first k.
std::vector<PhotonNeighbour> brute_force(const std::vector<Photon>& photons, const Vec3& p,
                                         std::size_t k, double radius_m) {
  std::vector<std::pair<double, std::uint32_t>> all;
  for (std::size_t i = 0; i < photons.size(); ++i) {
    const double d2 = photon_distance2_m2(photons[i], p);
    if (d2 <= radius_m * radius_m) all.emplace_back(d2, static_cast<std::uint32_t>(i));
  }
  std::sort(all.begin(), all.end());
  if (all.size() > k) all.resize(k);
  std::vector<PhotonNeighbour> out;
  for (const auto& [d2, i] : all) out.push_back({i, static_cast<float>(d2)});
  return out;
}

// Identical index sequences and bit-identical distances.
void expect_same(const std::vector<PhotonNeighbour>& got, const std::vector<PhotonNeighbour>& want,
                 const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].index, want[i].index) << what << " at rank " << i;
    ASSERT_EQ(got[i].distance2_m2, want[i].distance2_m2) << what << " at rank " << i;
  }
}

std::string describe(const Vec3& p, double r, int k = -1) {
  return "query (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
         ") r=" + std::to_string(r) + (k >= 0 ? " k=" + std::to_string(k) : "");
}

// Radii for a point set: none, a few that hold a handful to most photons, and
// the integers 0..3, which on the lattice set fall exactly on photons.
std::vector<double> radii_for(const std::vector<Photon>& photons) {
  std::vector<double> r = {kInf, 0.0, 1.0, 2.0, 3.0};
  if (photons.size() > 1) {
    const Vec3 extent = photons[0].position() - photons[photons.size() / 2].position();
    r.push_back(0.05 * length(extent) + 1e-3);
    r.push_back(0.3 * length(extent) + 1e-3);
  }
  return r;
}

// The photons as sortable tuples, to compare collections regardless of order.
std::vector<std::array<float, 7>> sorted_fields(const std::vector<Photon>& photons) {
  std::vector<std::array<float, 7>> v;
  for (const Photon& p : photons)
    v.push_back({p.position_m[0], p.position_m[1], p.position_m[2], p.direction[0], p.direction[1],
                 p.direction[2], p.power});
  std::sort(v.begin(), v.end());
  return v;
}

void check_against_brute_force(const std::vector<Photon>& given, int leaf_size,
                               const std::string& name) {
  const PhotonMap map(given, leaf_size);
  ASSERT_EQ(map.size(), given.size());
  // The map reorders the photons (leaf order); indices refer to its own copy.
  const std::vector<Photon>& photons = map.photons();
  ASSERT_EQ(sorted_fields(photons), sorted_fields(given)) << name;
  std::vector<PhotonNeighbour> got;
  const std::vector<int> ks = {1, 8, 50, 200, static_cast<int>(photons.size()) + 5};
  for (const Vec3& p : query_points(photons, 7)) {
    for (double r : radii_for(photons)) {
      for (int k : ks) {
        map.k_nearest(p, k, r, got);
        expect_same(got, brute_force(photons, p, k, r), name + " k_nearest " + describe(p, r, k));
        if (::testing::Test::HasFatalFailure()) return;
      }
      if (r < kInf) {
        map.within_radius(p, r, got);
        expect_same(got, brute_force(photons, p, photons.size(), r),
                    name + " within_radius " + describe(p, r));
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
}

TEST(Photon, LayoutAndAccessors) {
  EXPECT_EQ(sizeof(Photon), 28u);
  const Photon p{{1.5f, -2.0f, 3.25f}, {0.0f, 0.6f, 0.8f}, 7.0f};
  EXPECT_EQ(p.position(), Vec3(1.5, -2.0, 3.25));
  EXPECT_EQ(p.dir(), Vec3(0.0, static_cast<double>(0.6f), static_cast<double>(0.8f)));
  EXPECT_EQ(p.power, 7.0f);
}

TEST(PhotonMap, MatchesBruteForceUniformBox) {
  check_against_brute_force(uniform_box(3000, 1), 16, "uniform");
}

TEST(PhotonMap, MatchesBruteForceGaussianBlobs) {
  check_against_brute_force(gaussian_blobs(3000, 2), 16, "blobs");
}

TEST(PhotonMap, MatchesBruteForceWithDuplicatesAndTies) {
  // 1500 photons on 125 lattice sites: ~12 photons per site, and from lattice
  // queries whole shells of equal distance, so the k-th place is usually a tie.
  check_against_brute_force(lattice_duplicates(1500, 3), 16, "lattice");
}

TEST(PhotonMap, MatchesBruteForceFarFromTheOrigin) {
  // A 1 m box 3e4 m out: floats there are 2-4 mm apart, so positions collapse
  // onto a coarse grid (duplicates, equal distances) and the tree's pruning
  // distances are differences of large numbers.
  std::vector<Photon> photons = uniform_box(2000, 15);
  for (Photon& p : photons) {
    p.position_m[0] = 30000.0f + p.position_m[0] / 10;
    p.position_m[1] = -20000.0f + p.position_m[1] / 4;
    p.position_m[2] = 1000.0f + p.position_m[2] / 30;
  }
  check_against_brute_force(photons, 16, "far");
}

TEST(PhotonMap, MatchesBruteForceOnAPlane) {
  check_against_brute_force(plane(2000, 4), 16, "plane");
}

TEST(PhotonMap, MatchesBruteForceForOtherLeafSizes) {
  check_against_brute_force(uniform_box(1000, 5), 1, "uniform leaf 1");
  check_against_brute_force(lattice_duplicates(800, 6), 1, "lattice leaf 1");
  check_against_brute_force(gaussian_blobs(1000, 7), 64, "blobs leaf 64");
}

TEST(PhotonMap, AllPhotonsAtOnePoint) {
  // Every distance equal: results are the lowest indices, in order.
  check_against_brute_force(std::vector<Photon>(300, photon_at(1, 1, 1)), 16, "one site");
}

TEST(PhotonMap, OnePhoton) {
  check_against_brute_force({photon_at(0.25, -3, 8)}, 16, "one photon");
}

TEST(PhotonMap, NoPhotons) {
  const PhotonMap map({});
  EXPECT_EQ(map.size(), 0u);
  EXPECT_TRUE(map.photons().empty());
  std::vector<PhotonNeighbour> out = {{3, 1.0f}};  // stale content must be cleared
  map.k_nearest({0, 0, 0}, 10, kInf, out);
  EXPECT_TRUE(out.empty());
  out = {{3, 1.0f}};
  map.within_radius({0, 0, 0}, 1e9, out);
  EXPECT_TRUE(out.empty());
}

TEST(PhotonMap, ExactRadiusBoundaryIsIncluded) {
  // Photons at distance exactly 1 and 2 from the origin (exact in float and
  // double), and one just beyond 1; the radius test is distance² <= r².
  const PhotonMap map(
      {photon_at(0, 0, 2), photon_at(1, 0, 0), photon_at(0, -1, 0), photon_at(0, 0, 1.0000001)});
  auto position = [&](const PhotonNeighbour& n) { return map[n.index].position(); };
  std::vector<PhotonNeighbour> out;
  map.within_radius({0, 0, 0}, 1.0, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].distance2_m2, 1.0f);
  EXPECT_EQ(out[1].distance2_m2, 1.0f);
  EXPECT_LT(out[0].index, out[1].index);  // a tie: the smaller index first
  EXPECT_EQ(std::abs(position(out[0]).x) + std::abs(position(out[0]).y), 1.0);
  map.k_nearest({0, 0, 0}, 10, 2.0, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(position(out[3]), Vec3(0, 0, 2));
  EXPECT_EQ(out[3].distance2_m2, 4.0f);
  map.k_nearest({0, 0, 0}, 10, 1.9999999, out);
  EXPECT_EQ(out.size(), 3u);
  // Radius 0 keeps only a photon exactly at the point: 1.0000001f is not 1.
  map.within_radius({0, 0, 1}, 0.0, out);
  EXPECT_EQ(out.size(), 0u);
  map.within_radius({0, 0, 2}, 0.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(position(out[0]), Vec3(0, 0, 2));
}

TEST(PhotonMap, HoldsTheGivenPhotonsInADeterministicOrder) {
  const std::vector<Photon> photons = gaussian_blobs(5000, 8);
  const PhotonMap a(photons), b(photons);
  ASSERT_EQ(a.size(), photons.size());
  EXPECT_EQ(sorted_fields(a.photons()), sorted_fields(photons));
  // Same input, same order: results (and their tie-breaks) repeat run to run.
  bool moved = false;
  for (std::size_t i = 0; i < photons.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a[i], &b[i], sizeof(Photon)), 0) << i;
    EXPECT_EQ(&a[i], &a.photons()[i]);
    moved = moved || a[i].position() != photons[i].position();
  }
  EXPECT_TRUE(moved)
      << "expected leaf order to differ from the input order for 5000 scattered photons";
}

TEST(PhotonMap, MovedMapStillAnswers) {
  const std::vector<Photon> photons = uniform_box(400, 9);
  PhotonMap a(photons);
  std::vector<PhotonNeighbour> before, after;
  a.k_nearest({0, 0, 15}, 20, kInf, before);
  PhotonMap b(std::move(a));
  b.k_nearest({0, 0, 15}, 20, kInf, after);
  expect_same(after, before, "moved");
  PhotonMap c({});
  c = std::move(b);
  c.k_nearest({0, 0, 15}, 20, kInf, after);
  expect_same(after, before, "move-assigned");
}

TEST(PhotonMap, RejectsBadInput) {
  std::vector<Photon> bad = uniform_box(10, 10);
  bad[4].position_m[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(PhotonMap{bad}, Error);
  bad[4].position_m[1] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(PhotonMap{bad}, Error);
  EXPECT_THROW(PhotonMap(uniform_box(10, 10), 0), Error);

  const PhotonMap map(uniform_box(10, 10));
  std::vector<PhotonNeighbour> out;
  EXPECT_THROW(map.k_nearest({0, 0, 0}, -1, kInf, out), Error);
  EXPECT_THROW(map.k_nearest({0, 0, 0}, 3, -1.0, out), Error);
  EXPECT_THROW(map.k_nearest({0, 0, 0}, 3, std::nan(""), out), Error);
  EXPECT_THROW(map.within_radius({0, 0, 0}, -0.5, out), Error);
  EXPECT_THROW(map.within_radius({kInf, 0, 0}, 1.0, out), Error);
  map.k_nearest({0, 0, 0}, 0, kInf, out);
  EXPECT_TRUE(out.empty());
}

TEST(PhotonMap, ConcurrentQueriesMatchSerial) {
  const std::vector<Photon> photons = gaussian_blobs(20000, 11);
  const PhotonMap map(photons);
  std::vector<Vec3> queries;
  Rng rng(12, 0);
  for (int i = 0; i < 600; ++i)
    queries.push_back(photons[static_cast<std::size_t>(rng.uniform() * photons.size())].position() +
                      Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5});
  // Serial answers: k-NN (k = 50) and radius queries alternately, so each
  // thread's scratch buffer switches between the two kinds.
  auto run = [&](std::size_t i, std::vector<PhotonNeighbour>& out) {
    if (i % 2 == 0)
      map.k_nearest(queries[i], 50, 2.0, out);
    else
      map.within_radius(queries[i], 0.3, out);
  };
  std::vector<std::vector<PhotonNeighbour>> serial(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) run(i, serial[i]);

  constexpr int kThreads = 8;
  std::vector<std::vector<std::vector<PhotonNeighbour>>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      // Each thread walks the queries from a different start, three times over.
      results[t].resize(queries.size());
      for (int pass = 0; pass < 3; ++pass)
        for (std::size_t j = 0; j < queries.size(); ++j) {
          const std::size_t i = (j + static_cast<std::size_t>(t) * 97) % queries.size();
          run(i, results[t][i]);
        }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t i = 0; i < queries.size(); ++i) {
      expect_same(results[t][i], serial[i],
                  "thread " + std::to_string(t) + " query " + std::to_string(i));
      if (::testing::Test::HasFatalFailure()) return;
    }
}

TEST(PhotonMap, HugeRadiusReturnsEverythingAndLaterQueriesStillMatch) {
  // 100 000 results overflow the per-thread scratch limit (1 MiB), which is
  // then released; the next queries on this thread must still be right.
  const PhotonMap map(uniform_box(100000, 16));
  std::vector<PhotonNeighbour> out;
  map.within_radius({0, 0, 15}, 1e6, out);
  ASSERT_EQ(out.size(), map.size());
  expect_same(out, brute_force(map.photons(), {0, 0, 15}, map.size(), 1e6), "everything");
  map.k_nearest({1, 1, 1}, 200, kInf, out);
  expect_same(out, brute_force(map.photons(), {1, 1, 1}, 200, kInf), "after release");
}

TEST(PhotonMap, MemoryGrowsWithSize) {
  std::size_t previous = PhotonMap({}).memory_bytes();
  for (int n : {1, 1000, 10000, 100000}) {
    const PhotonMap map(uniform_box(n, 13));
    const std::size_t bytes = map.memory_bytes();
    EXPECT_GT(bytes, previous) << n;
    // At least the photons and the tree's 4-byte index per photon; the nodes
    // (one per ~leaf_size/2 photons, two children each) stay well below
    // another 28 bytes per photon once there are many photons.
    EXPECT_GE(bytes, static_cast<std::size_t>(n) * (sizeof(Photon) + 4)) << n;
    if (n >= 1000) {
      EXPECT_LT(bytes, static_cast<std::size_t>(n) * (2 * sizeof(Photon) + 4)) << n;
    }
    previous = bytes;
  }
}

TEST(PhotonMap, SmallerLeavesCostMoreNodeMemory) {
  // The node count is measured, not assumed: leaf size 1 needs about as many
  // leaves as photons, leaf size 32 far fewer.
  const std::vector<Photon> photons = uniform_box(20000, 14);
  EXPECT_GT(PhotonMap(photons, 1).memory_bytes(),
            PhotonMap(photons, 32).memory_bytes() + 20000 * 16);
}

}  // namespace
}  // namespace obscura
