// Photon map (photon/photon_map.h): build time, k-nearest and fixed-radius
// queries per second, and memory per photon, for photon clouds of 1e5, 1e6 and
// 4e6 photons. Prints the figures (docs/photon-map.md); nothing is asserted.
//   bench_photon_map [--sizes 100000,1000000,4000000] [--queries 100000] [--leaf 16] [--threads N]
//
// The cloud is a Gaussian puff (σ = 5 m about the origin), the shape of a
// smoke cloud's photon distribution: dense in the core, sparse at the edge.
// Query points are drawn from the same distribution, so they lie inside the
// cloud where the radiance estimate asks. The radius query uses the median
// distance to the 50th neighbour, so it returns about as many photons as the
// k = 50 query. Single-thread figures use one thread; the "threads" column
// runs the same queries split over N std::threads (default: all cores).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_timer.h"
#include "obscura/core/rng.h"
#include "obscura/render/photon_map/photon_map.h"

using namespace obscura;
using bench::seconds_since;

namespace {

Vec3 gaussian_point(Rng& rng, double sigma_m) {
  Vec3 g;
  for (int a = 0; a < 3; ++a) {  // Box–Muller, one normal per axis
    const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();
    g[a] = sigma_m * std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
  }
  return g;
}

std::vector<Photon> make_cloud(std::size_t n, double sigma_m) {
  Rng rng(1, 0);
  std::vector<Photon> photons(n);
  for (Photon& p : photons) {
    const Vec3 x = gaussian_point(rng, sigma_m);
    const Vec3 d = normalize(gaussian_point(rng, 1.0));
    p = Photon{{float(x.x), float(x.y), float(x.z)}, {float(d.x), float(d.y), float(d.z)}, 1.0f};
  }
  return photons;
}

// Runs query(i, out) for i in [0, n) on `threads` threads (contiguous
// blocks); returns wall seconds and adds the number of photons found to *found.
template <class Query>
double run_queries(std::size_t n, int threads, Query query, double* found) {
  std::vector<double> counts(threads, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      std::vector<PhotonNeighbour> out;
      const std::size_t begin = n * t / threads, end = n * (t + 1) / threads;
      double c = 0;
      for (std::size_t i = begin; i < end; ++i) {
        query(i, out);
        c += static_cast<double>(out.size());
      }
      counts[t] = c;
    });
  }
  for (std::thread& th : pool) th.join();
  const double s = seconds_since(t0);
  for (double c : counts) *found += c;
  return s;
}

std::vector<std::size_t> parse_sizes(const std::string& list) {
  std::vector<std::size_t> sizes;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    sizes.push_back(static_cast<std::size_t>(std::atof(item.c_str())));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes = {100000, 1000000, 4000000};
  std::size_t queries = 100000;
  int leaf = 16;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--sizes")
      sizes = parse_sizes(argv[i + 1]);
    else if (a == "--queries")
      queries = static_cast<std::size_t>(std::atof(argv[i + 1]));
    else if (a == "--leaf")
      leaf = std::atoi(argv[i + 1]);
    else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  constexpr double kSigma = 5.0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::printf(
      "photon map benchmark: Gaussian cloud sigma %.0f m, leaf size %d, %zu queries per figure, "
      "%d threads for the threaded column\n",
      kSigma, leaf, queries, threads);
  std::printf("%10s %9s %9s | %-26s | %-26s | %-34s\n", "photons", "build s", "B/photon",
              "kNN k=50: q/s 1 thr, N thr", "kNN k=200: q/s 1 thr, N thr",
              "radius r: q/s 1 thr, N thr, mean found");

  for (std::size_t n : sizes) {
    std::vector<Photon> photons = make_cloud(n, kSigma);
    const auto t0 = std::chrono::steady_clock::now();
    const PhotonMap map(std::move(photons), leaf);
    const double build_s = seconds_since(t0);
    const double bytes_per_photon =
        static_cast<double>(map.memory_bytes()) / static_cast<double>(n);

    Rng rng(2, 0);
    std::vector<Vec3> points(queries);
    for (Vec3& p : points) p = gaussian_point(rng, kSigma);

    // Radius: the median 50th-neighbour distance over (up to) 1000 of the points.
    std::vector<double> d50;
    std::vector<PhotonNeighbour> out;
    for (std::size_t i = 0; i < std::min<std::size_t>(1000, queries); ++i) {
      map.k_nearest(points[i], 50, kInf, out);
      if (!out.empty()) d50.push_back(std::sqrt(static_cast<double>(out.back().distance2_m2)));
    }
    std::nth_element(d50.begin(), d50.begin() + d50.size() / 2, d50.end());
    const double radius = d50.empty() ? 1.0 : d50[d50.size() / 2];

    auto knn = [&](int k) {
      return [&, k](std::size_t i, std::vector<PhotonNeighbour>& o) {
        map.k_nearest(points[i], k, kInf, o);
      };
    };
    auto within = [&](std::size_t i, std::vector<PhotonNeighbour>& o) {
      map.within_radius(points[i], radius, o);
    };

    double found = 0, found_radius = 0;
    const double q = static_cast<double>(queries);
    const double k50_1 = q / run_queries(queries, 1, knn(50), &found);
    const double k50_n = q / run_queries(queries, threads, knn(50), &found);
    const double k200_1 = q / run_queries(queries, 1, knn(200), &found);
    const double k200_n = q / run_queries(queries, threads, knn(200), &found);
    const double r_1 = q / run_queries(queries, 1, within, &found_radius);
    const double r_n = q / run_queries(queries, threads, within, &found);
    std::printf(
        "%10zu %9.3f %9.1f | %12.3g %12.3g | %12.3g %12.3g | r=%.4g m %10.3g %10.3g %8.1f\n", n,
        build_s, bytes_per_photon, k50_1, k50_n, k200_1, k200_n, radius, r_1, r_n,
        found_radius / q);
  }
  return 0;
}
