// MeshSurface (Embree) against a brute-force reference, and the precision
// cases the integrators rely on: leaving a surface 1e-9 m off it, and rays
// kilometres long.
#include "obscura/scene/mesh_surface.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "obscura/core/error.h"
#include "obscura/io/obj_mesh.h"

namespace obscura {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Möller & Trumbore (1997) in double precision, one triangle; t in (t_min, t_max).
bool moller_trumbore(const Vec3& a, const Vec3& b, const Vec3& c, const Ray& ray, double t_min,
                     double t_max, double& t) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = cross(ray.direction, e2);
  const double det = dot(e1, p);
  if (det == 0) return false;
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - a;
  const double u = dot(s, p) * inv;
  if (u < 0 || u > 1) return false;
  const Vec3 q = cross(s, e1);
  const double v = dot(ray.direction, q) * inv;
  if (v < 0 || u + v > 1) return false;
  t = dot(e2, q) * inv;
  return t > t_min && t < t_max;
}

struct RefHit {
  double t;
  Vec3 normal;  // unit, facing the ray
};

// The triangle grown (margin_m > 0) or shrunk (< 0) by |margin_m| metres at
// every edge: where the ray meets its plane must be that close to inside.
bool near_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Ray& ray, double t_min,
                   double t_max, double margin_m, double& t) {
  const Vec3 n = cross(b - a, c - a);
  const double dn = dot(n, ray.direction);
  if (dn == 0) return false;
  t = dot(n, a - ray.origin) / dn;
  if (!(t > t_min && t < t_max)) return false;
  const Vec3 p = ray.at(t);
  const Vec3 corner[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 inward = normalize(cross(n, corner[(k + 1) % 3] - corner[k]));
    if (dot(p - corner[k], inward) < -margin_m) return false;
  }
  return true;
}

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// Every hit with t in the window, over every triangle but `skip` (the ray's
// source): Möller–Trumbore when margin_m is 0, else near_triangle.
std::vector<RefHit> brute_force(const TriangleMesh& m, const Ray& ray, double t_min, double t_max,
                                double margin_m = 0, std::size_t skip = kNone) {
  std::vector<RefHit> hits;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    if (i == skip) continue;
    const auto& tri = m.triangles[i];
    const Vec3 &a = m.vertices[tri[0]], &b = m.vertices[tri[1]], &c = m.vertices[tri[2]];
    double t;
    const bool hit = margin_m == 0
                         ? moller_trumbore(a, b, c, ray, std::max(t_min, 0.0), t_max, t)
                         : near_triangle(a, b, c, ray, std::max(t_min, 0.0), t_max, margin_m, t);
    if (!hit) continue;
    const Vec3 n = normalize(cross(b - a, c - a));
    hits.push_back({t, dot(n, ray.direction) > 0 ? -n : n});
  }
  return hits;
}

double nearest(const std::vector<RefHit>& hits) {
  double t = kInf;
  for (const auto& h : hits) t = std::min(t, h.t);
  return t;
}

// Whether `hit` is one of `hits` (t to 1e-5 relative, the same normal) and,
// with `first`, one at the nearest t.
bool among(const SurfaceHit& hit, const std::vector<RefHit>& hits, bool first) {
  const double t0 = nearest(hits);
  for (const auto& h : hits)
    if ((!first || h.t <= t0 * (1 + 1e-6)) && std::abs(h.t - hit.t) <= 1e-5 * h.t &&
        length(h.normal - hit.normal) < 1e-9)
      return true;
  return false;
}

// How MeshSurface's answer compares with the brute force: the same (kAgree);
// different only because the ray passes within edge_m of a triangle's edge,
// which Embree's single precision cannot decide (kEdge: a hit must then be a
// hit of the grown triangles with none of the shrunk ones nearer, a miss must
// miss every shrunk triangle); or wrong (kWrong).
enum class Verdict { kAgree, kEdge, kWrong };

Verdict judge(const MeshSurface& s, const TriangleMesh& m, const Ray& ray, double t_min,
              double t_max, double edge_m, std::size_t skip = kNone) {
  SurfaceHit hit;
  const bool got = s.intersect(ray, t_min, t_max, hit);
  if (got && !(dot(hit.normal, ray.direction) < 0)) return Verdict::kWrong;
  const auto exact = brute_force(m, ray, t_min, t_max, 0, skip);
  if (got ? among(hit, exact, true) : exact.empty()) return Verdict::kAgree;
  const auto shrunk = brute_force(m, ray, t_min, t_max, -edge_m, skip);
  if (!got) return shrunk.empty() ? Verdict::kEdge : Verdict::kWrong;
  const bool ok = among(hit, brute_force(m, ray, t_min, t_max, edge_m, skip), false) &&
                  hit.t <= nearest(shrunk) * (1 + 1e-5);
  return ok ? Verdict::kEdge : Verdict::kWrong;
}

// Verdicts over many rays: none may be wrong, and at most `edge_share` of
// them decided by float at an edge.
struct Tally {
  int agree = 0, edge = 0, wrong = 0;
  void add(Verdict v, const std::string& what) {
    if (v == Verdict::kAgree) ++agree;
    if (v == Verdict::kEdge) ++edge;
    if (v == Verdict::kWrong) {
      ++wrong;
      ADD_FAILURE() << what;
    }
  }
  void check(double edge_share) const {
    EXPECT_EQ(wrong, 0);
    EXPECT_LE(edge, edge_share * (agree + edge + wrong)) << edge << " answers decided at an edge";
    std::printf("%d rays agree with the brute force, %d differ within float precision of an edge\n",
                agree, edge);
  }
};

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalize(Vec3(g(rng), g(rng), g(rng)));
}

Vec3 random_in(std::mt19937_64& rng, const BBox3& b) {
  std::uniform_real_distribution<double> u(0, 1);
  return {b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
          b.lo.z + u(rng) * (b.hi.z - b.lo.z)};
}

// A window: the whole ray, from a point along it, or up to one.
void random_window(std::mt19937_64& rng, int i, double scale, double& t_min, double& t_max) {
  std::uniform_real_distribution<double> u(0, 1);
  t_min = 0;
  t_max = kInf;
  if (i % 3 == 1) t_min = u(rng) * scale;
  if (i % 3 == 2) t_max = u(rng) * scale;
}

TriangleMesh random_soup(int triangles, unsigned seed) {
  std::mt19937_64 rng(seed);
  const BBox3 box({-5, -5, -5}, {5, 5, 5});
  TriangleMesh m;
  m.part_names = {"soup"};
  for (int i = 0; i < triangles; ++i) {
    const Vec3 c = random_in(rng, box);
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + random_unit(rng) * 1.5);
    const auto b = static_cast<std::uint32_t>(3 * i);
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangle_part.push_back(0);
  }
  return m;
}

TriangleMesh tank() {
  return read_obj_mesh(std::string(OBSCURA_SOURCE_DIR) + "/examples/tank/tank.obj");
}

// Float decides hits within this distance of an edge: 1e-6 of the mesh's size.
double edge_band(const TriangleMesh& m) { return 1e-6 * length(m.bounds().extent()); }

TEST(MeshSurface, MatchesBruteForceOnARandomSoup) {
  const TriangleMesh soup = random_soup(300, 5);
  const MeshSurface s("soup", {300, 1}, soup);
  EXPECT_EQ(s.triangle_count(), 300u);
  std::mt19937_64 rng(11);
  const BBox3 around({-9, -9, -9}, {9, 9, 9});
  Tally tally;
  int hits = 0;
  for (int i = 0; i < 12000; ++i) {
    const Ray ray{random_in(rng, around), random_unit(rng)};
    double t_min, t_max;
    random_window(rng, i, 12.0, t_min, t_max);
    tally.add(judge(s, soup, ray, t_min, t_max, edge_band(soup)), "ray " + std::to_string(i));
    SurfaceHit h;
    hits += s.intersect(ray, t_min, t_max, h);
  }
  tally.check(1e-3);
  EXPECT_GT(hits, 1200);  // the comparison is not vacuous
}

TEST(MeshSurface, MatchesBruteForceOnTheTank) {
  const TriangleMesh m = tank();
  const MeshSurface s("tank", {300, 1}, m);
  std::mt19937_64 rng(23);
  const BBox3 b = m.bounds();
  Tally tally;
  int hits = 0;
  for (int i = 0; i < 12000; ++i) {
    // From 20 m around, towards a point of the tank's box (most rays hit), or anywhere.
    const Vec3 o = b.center() + random_unit(rng) * 20.0;
    const Vec3 d = i % 4 == 3 ? random_unit(rng) : normalize(random_in(rng, b) - o);
    double t_min, t_max;
    random_window(rng, i, 25.0, t_min, t_max);
    tally.add(judge(s, m, Ray{o, d}, t_min, t_max, edge_band(m)), "ray " + std::to_string(i));
    SurfaceHit h;
    hits += s.intersect(Ray{o, d}, t_min, t_max, h);
  }
  tally.check(1e-3);
  EXPECT_GT(hits, 4000);
}

// A ray leaving a triangle from a point lifted 1e-9 m along its normal (what
// the integrators do), steeply or grazing, must find what a brute force that
// skips the triangle finds: a hit on the triangle itself is wrong, never
// excused as an edge case.
void expect_no_self_hits(const TriangleMesh& m, unsigned seed) {
  const MeshSurface s("m", {300, 1}, m);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  const double lifts[] = {1.0, 1e-2, 1e-4, 1e-6};
  Tally steep, grazing;  // lifts 1 and 1e-2; 1e-4 and 1e-6 (float decides more edges)
  for (int i = 0; i < 4000; ++i) {
    const std::size_t k = pick(rng);
    const auto& tri = m.triangles[k];
    const Vec3 &a = m.vertices[tri[0]], &b = m.vertices[tri[1]], &c = m.vertices[tri[2]];
    double r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
    const Vec3 p = a + (b - a) * r1 + (c - a) * r2;
    Vec3 n = normalize(cross(b - a, c - a));
    if (i % 2) n = -n;  // either side
    // A direction into n's hemisphere, from steep to grazing.
    const Vec3 d = normalize(normalize(cross(n, random_unit(rng))) + n * lifts[i % 4]);
    const Ray ray{p + n * 1e-9, d};
    const double t_min = i % 8 < 4 ? 0.0 : 1e-9;
    SurfaceHit hit;
    if (s.intersect(ray, t_min, kInf, hit) && hit.t < 1e-6 && length(hit.normal + n) < 1e-9)
      ADD_FAILURE() << "ray " << i << " hit its own triangle " << k << " again at t " << hit.t;
    (i % 4 < 2 ? steep : grazing)
        .add(judge(s, m, ray, t_min, kInf, edge_band(m), k),
             "ray " + std::to_string(i) + " from triangle " + std::to_string(k) + ", lift " +
                 std::to_string(lifts[i % 4]));
  }
  steep.check(1e-3);
  grazing.check(2e-2);
}

TEST(MeshSurface, RaysLeavingASurfaceDoNotHitItAgain) {
  expect_no_self_hits(random_soup(200, 3), 31);
  expect_no_self_hits(tank(), 37);
  // The same far from the world origin (a georeferenced mesh).
  TriangleMesh far = tank();
  far.translate({4200.0, -3100.0, 250.0});
  expect_no_self_hits(far, 41);
}

TEST(MeshSurface, FarOriginHitsAtTheExactDistance) {
  const TriangleMesh m = tank();
  const MeshSurface s("tank", {300, 1}, m);
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200; ++i) {
    // A point on the turret roof (z = 2.4), seen from 2 km away and above.
    const Vec3 p(-1.0 + 2.0 * (i % 10) / 10.0, -1.5 + 3.0 * (i / 10) / 20.0, 2.4);
    Vec3 d = random_unit(rng);
    d.z = -std::abs(d.z) - 0.2;
    d = normalize(d);
    const Ray ray{p - d * 2000.0, d};
    SurfaceHit hit;
    ASSERT_TRUE(s.intersect(ray, 0.0, kInf, hit)) << i;
    EXPECT_NEAR(hit.t, 2000.0, 1e-6);
    EXPECT_NEAR(hit.normal.z, 1.0, 1e-12);
    // A window ending just before it misses; one starting just after finds what lies behind.
    EXPECT_FALSE(s.intersect(ray, 0.0, 1999.999, hit));
    if (s.intersect(ray, 2000.000001, kInf, hit)) {
      EXPECT_GT(hit.t, 2000.0);
    }
  }
}

// A ray with a NaN or infinite component never reaches Embree and hits
// nothing, whether or not its box test lets it through (the box test comes
// first: mesh_surface.cpp).
TEST(MeshSurface, RaysWithNonFiniteComponentsHitNothing) {
  const TriangleMesh m = tank();
  const MeshSurface s("tank", {300, 1}, m);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 towards = normalize(m.bounds().center() - Vec3(0, -20, 1));
  ASSERT_TRUE([&] {
    SurfaceHit hit;
    return s.intersect(Ray{Vec3(0, -20, 1), towards}, 0.0, kInf, hit);
  }());  // the finite ray hits
  for (const Ray& ray :
       {Ray{Vec3(nan, -20, 1), towards}, Ray{Vec3(0, -20, kInf), towards},
        Ray{Vec3(0, -20, 1), Vec3(towards.x, nan, towards.z)},
        Ray{Vec3(0, -20, 1), Vec3(0, kInf, 0)}, Ray{Vec3(0, 0, 1), Vec3(nan, nan, nan)}}) {
    SurfaceHit hit;
    EXPECT_FALSE(s.intersect(ray, 0.0, kInf, hit))
        << ray.origin.x << " " << ray.origin.y << " " << ray.origin.z << " → " << ray.direction.x
        << " " << ray.direction.y << " " << ray.direction.z;
  }
}

TEST(MeshSurface, RefusesAMeshWithoutArea) {
  TriangleMesh m;
  m.part_names = {"flat"};
  m.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  m.triangles = {{0, 1, 2}};
  m.triangle_part = {0};
  const SurfaceMaterial material{300, 1};
  EXPECT_THROW(MeshSurface("flat", material, m), Error);
}

// Not a pass/fail test: the throughput of Embree against the brute force on
// the tank, printed for docs/performance.md-style figures.
TEST(MeshSurface, ThroughputOnTheTank) {
  const TriangleMesh m = tank();
  const MeshSurface s("tank", {300, 1}, m);
  std::mt19937_64 rng(3);
  std::vector<Ray> rays;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 o = m.bounds().center() + random_unit(rng) * 20.0;
    rays.push_back({o, normalize(random_in(rng, m.bounds()) - o)});
  }
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  int hits = 0;
  for (const Ray& r : rays) {
    SurfaceHit h;
    hits += s.intersect(r, 0, kInf, h);
  }
  const double embree_s = std::chrono::duration<double>(clock::now() - t0).count();
  t0 = clock::now();
  int ref_hits = 0;
  for (std::size_t i = 0; i < rays.size() / 10; ++i)
    ref_hits += !brute_force(m, rays[i], 0, kInf).empty();
  const double brute_s = std::chrono::duration<double>(clock::now() - t0).count() * 10;
  std::printf("tank (%zu triangles): Embree %.3g rays/s, brute force %.3g rays/s (one thread)\n",
              m.triangle_count(), rays.size() / embree_s, rays.size() / brute_s);
  EXPECT_GT(hits, 0);
  EXPECT_GT(ref_hits, 0);
}

}  // namespace
}  // namespace obscura
