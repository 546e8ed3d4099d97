#include "obscura/render/photon_map/photon_tracing.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/memory_limit.h"
#include "obscura/core/parallel.h"
#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/direct_lighting.h"

namespace obscura {
namespace {

constexpr double kFourPi = 4.0 * std::numbers::pi;
constexpr long long kChunk = 2048;         // photons per parallel work item
constexpr int kEnvironmentPilot = 2048;    // samples estimating the environment's power
constexpr int kMaxLatticeCells = 1 << 18;  // emission lattice (64³)

// Volume emission 4π σa B(T) (W m⁻³ µm⁻¹) tabled at the centres of a lattice
// over the medium's box, to draw emission points from.
class EmissionLattice {
 public:
  EmissionLattice(const Medium& medium, const SpectralNode& node, int threads)
      : box_(medium.bounds()) {
    const Vec3 e = box_.extent();
    const double volume = std::max(e.x * e.y * e.z, 1e-300);
    const double h = std::cbrt(volume / kMaxLatticeCells);
    n_[0] = std::clamp(static_cast<int>(std::ceil(e.x / h)), 1, 512);
    n_[1] = std::clamp(static_cast<int>(std::ceil(e.y / h)), 1, 512);
    n_[2] = std::clamp(static_cast<int>(std::ceil(e.z / h)), 1, 512);
    cell_ = Vec3(e.x / n_[0], e.y / n_[1], e.z / n_[2]);
    const std::size_t count = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
    std::vector<double> f(count, 0.0);
    const SpectralLerp lambda = node.lerp();
    // Tiles of kTile³ cells whose centres' box the medium leaves empty
    // (its majorants) are zero without evaluating a point, as is B(T) where
    // σa is: the values are the same, and a cloud fills a small part of its
    // box (docs/performance.md). Rows of tiles on the threads: each cell's
    // value is its own, whatever the thread.
    constexpr int kTile = 8;
    auto fill_tile = [&](const int lo[3], const int end[3], MediumPoint& point) {
      for (int k = lo[2]; k < end[2]; ++k)
        for (int j = lo[1]; j < end[1]; ++j)
          for (int i = lo[0]; i < end[0]; ++i) {
            medium.coefficients_of_samples(center(i, j, k), lambda.sample0, lambda.sample1, point);
            const double sigma_a = lambda(point.sigma_a.data());
            if (sigma_a != 0.0)
              f[index(i, j, k)] = kFourPi * sigma_a * node.planck(point.temperature_k);
          }
    };
    const int tiles_y = (n_[1] + kTile - 1) / kTile, tiles_z = (n_[2] + kTile - 1) / kTile;
    parallel_for(static_cast<std::size_t>(tiles_y) * tiles_z, threads, [&](std::size_t row) {
      const int tj = static_cast<int>(row % tiles_y) * kTile,
                tk = static_cast<int>(row / tiles_y) * kTile;
      MediumPoint point;
      for (int ti = 0; ti < n_[0]; ti += kTile) {
        const int lo[3] = {ti, tj, tk};
        const int end[3] = {std::min(ti + kTile, n_[0]), std::min(tj + kTile, n_[1]),
                            std::min(tk + kTile, n_[2])};
        if (medium.may_be_nonzero(
                BBox3(center(ti, tj, tk), center(end[0] - 1, end[1] - 1, end[2] - 1))))
          fill_tile(lo, end, point);
      }
    });
    // Summed in the cells' order, whatever the tiles.
    double sum = 0;
    for (std::size_t c = 0; c < count; ++c) sum += f[c];
    if (!(sum > 0)) return;
    // A defensive 1 % of the mean in every cell: the continuous field may be
    // non-zero in a cell whose centre value is zero.
    const double floor = 0.01 * sum / count;
    cdf_.resize(count + 1, 0.0);
    for (std::size_t c = 0; c < count; ++c) cdf_[c + 1] = cdf_[c] + f[c] + floor;
    estimated_power_ = sum * cell_.x * cell_.y * cell_.z;
  }

  // Spectral power ≈ Σ f(centre) × cell volume, W µm⁻¹ (0: nothing emits).
  double estimated_power() const { return estimated_power_; }

  // A point with its density (per m³).
  Vec3 sample(Rng& rng, double* pdf) const {
    const double u = rng.uniform() * cdf_.back();
    const std::size_t c =
        std::min<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(),
                              cdf_.size() - 1) -
        1;
    *pdf = (cdf_[c + 1] - cdf_[c]) / cdf_.back() / (cell_.x * cell_.y * cell_.z);
    const Vec3 corner = center(c) - cell_ * 0.5;
    return corner + Vec3(rng.uniform() * cell_.x, rng.uniform() * cell_.y, rng.uniform() * cell_.z);
  }

 private:
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(n_[0]) * (j + static_cast<std::size_t>(n_[1]) * k);
  }
  Vec3 center(int i, int j, int k) const {
    return box_.lo + Vec3((i + 0.5) * cell_.x, (j + 0.5) * cell_.y, (k + 0.5) * cell_.z);
  }
  Vec3 center(std::size_t c) const {
    return center(static_cast<int>(c % n_[0]), static_cast<int>((c / n_[0]) % n_[1]),
                  static_cast<int>(c / (static_cast<std::size_t>(n_[0]) * n_[1])));
  }
  BBox3 box_;
  int n_[3] = {1, 1, 1};
  Vec3 cell_;
  std::vector<double> cdf_;
  double estimated_power_ = 0;
};

// A point uniform on the disc of radius r centred at c across direction d.
Vec3 point_on_disc(const Vec3& c, const Vec3& d, double r, Rng& rng) {
  const double rho = r * std::sqrt(rng.uniform()), phi = 2.0 * std::numbers::pi * rng.uniform();
  return c + local_to_world(d, Vec3(rho * std::cos(phi), rho * std::sin(phi), 0.0));
}

enum Source { kSun = 0, kEnvironment = 1, kEmission = 2 };

struct Launch {
  Ray ray;
  double power = 0;          // W µm⁻¹
  bool scattered = false;    // counts as scattered already (emission photons)
  bool store_first = false;  // store its first scattering although it has not scattered yet
  bool from_sky = false;     // an environment photon from the sky (not from a surface)
};

// The environment photons of one line, one per piece of it between the
// surfaces it crosses in the medium's box (PhotonSources::environment).
struct EnvironmentLaunches {
  static constexpr int kMaxPieces = 8;  // beyond, the line's further pieces are dropped
  std::array<Launch, kMaxPieces> launch;
  int count = 0;
  void add(const Launch& l) { launch[static_cast<std::size_t>(count++)] = l; }
  double power() const {
    double sum = 0;
    for (int i = 0; i < count; ++i) sum += launch[static_cast<std::size_t>(i)].power;
    return sum;
  }
};

// A photon's journey after launch: free flights by delta tracking, stored at
// scattering events (all of them with store_first_scatter, else from the
// second on for sun and environment photons), Russian roulette by the
// albedo at collisions (or absorption by weight, below) and by the
// reflectance at surfaces.
//
// Absorption by weight (absorb_by_weight; "implicit capture", survival
// biasing; Spanier & Gelbard 1969, §3): at a real collision the power is
// multiplied by the albedo Λ = σs/σt rather than the photon ended with
// probability 1 − Λ; once it falls below kRouletteShare of the launch
// power P₀, Russian roulette keeps it with probability P/(kRouletteShare P₀)
// at kRouletteShare P₀. Both keep the expected power at every collision, so
// the estimates are unchanged in expectation; every photon contributes
// more flights, each of less power: on the smoke cube (albedo 0.9) the
// radiance cache's error at 8·10⁵ photons fell from 2.56 % to 2.02 %
// (three seeds) for 23 % more time (docs/performance.md).
constexpr double kRouletteShare = 0.5;

// What one chunk of photons keeps: stored photons, or their flights.
struct ChunkRecord {
  std::vector<Photon> photons;
  std::vector<PhotonFlight> flights;
  std::vector<SurfaceDeposit> deposits;
  PhotonWalks walks;
};

PhotonFlight flight_of(const Ray& ray, double length_m, double power) {
  return {{static_cast<float>(ray.origin.x), static_cast<float>(ray.origin.y),
           static_cast<float>(ray.origin.z)},
          {static_cast<float>(ray.direction.x), static_cast<float>(ray.direction.y),
           static_cast<float>(ray.direction.z)},
          static_cast<float>(length_m),
          static_cast<float>(power)};
}

void trace_photon(const Scene& scene, const SpectralNode& node, const SpectralLerp& lambda,
                  const Launch& l, const PhotonTracingSettings& settings, Rng& rng,
                  MediumPoint& scratch, ChunkRecord& record) {
  Ray ray = l.ray;
  bool scattered = l.scattered;
  double power = l.power;
  auto deposit = [&](const Vec3& x, double p, int surface) {
    record.deposits.push_back(
        SurfaceDeposit{{static_cast<float>(x.x), static_cast<float>(x.y), static_cast<float>(x.z)},
                       static_cast<float>(p),
                       static_cast<std::int32_t>(surface)});
  };
  ++record.walks.photons;
  bool collided = false;
  for (int bounce = 0; bounce < settings.max_scatterings; ++bounce) {
    SurfaceHit hit;
    const bool on_surface =
        intersect_surfaces(scene.surfaces, ray, 1e-9, std::numeric_limits<double>::infinity(), hit);
    const auto t = sample_free_flight(*scene.medium, ray,
                                      on_surface ? hit.t : std::numeric_limits<double>::infinity(),
                                      lambda, rng, scratch);
    const bool counts = scattered || l.store_first || settings.store_first_scatter;
    if (settings.flights && counts) {
      // To the collision, else to the surface or out of the medium's box.
      double end = t ? *t : on_surface ? hit.t : 0.0;
      if (!t) {
        double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
        if (scene.medium->bounds().intersect(ray, t0, t1))
          end = on_surface ? std::min(end, t1) : t1;
        else
          end = 0.0;
      }
      if (end > 0.0) record.flights.push_back(flight_of(ray, end, power));
    }
    // A sky photon's first collision takes its power from the straight line
    // to the surface beyond, which the surface's own radiance counts as
    // arriving.
    if (settings.surface_deposits && t && on_surface && l.from_sky && !scattered)
      deposit(ray.at(hit.t), -power, hit.surface);
    if (t) {
      ++record.walks.collisions;
      if (!collided) ++record.walks.colliding;
      collided = true;
      const double sigma_a = lambda(scratch.sigma_a.data()),
                   sigma_s = lambda(scratch.sigma_s.data());
      if (settings.absorb_by_weight) {
        power *= sigma_s / (sigma_a + sigma_s);
        if (!(power > 0.0)) return;
        if (power < kRouletteShare * l.power) {
          if (rng.uniform() * kRouletteShare * l.power >= power) return;  // absorbed
          power = kRouletteShare * l.power;
        }
      } else if (rng.uniform() * (sigma_a + sigma_s) >= sigma_s) {
        return;  // absorbed
      }
      const Vec3 x = ray.at(*t);
      if (counts && !settings.flights)
        record.photons.push_back(
            Photon{{static_cast<float>(x.x), static_cast<float>(x.y), static_cast<float>(x.z)},
                   {static_cast<float>(ray.direction.x), static_cast<float>(ray.direction.y),
                    static_cast<float>(ray.direction.z)},
                   static_cast<float>(power)});
      scattered = true;
      const HenyeyGreenstein phase(std::clamp(lambda(scratch.g.data()), -0.999999, 0.999999));
      ray = Ray{x, phase.sample(ray.direction, rng.uniform(), rng.uniform(), nullptr)};
    } else if (on_surface) {
      if (!scattered) return;  // its reflection is in the surface's own radiance
      if (settings.surface_deposits) deposit(ray.at(hit.t), power, hit.surface);
      const double reflectance =
          scene.surfaces[hit.surface]->material().reflectance_at(node.wavelength_um);
      if (rng.uniform() >= reflectance) return;
      ray = Ray{ray.at(hit.t) + hit.normal * 1e-9,
                local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
    } else {
      return;  // escaped
    }
  }
}

// The three sources of one spectral node and how a photon leaves each.
class PhotonSources {
 public:
  PhotonSources(const Scene& scene, const SpectralNode& node, double lateral_period_m, int threads)
      : scene_(scene),
        node_(node),
        lambda_(node.lerp()),
        sphere_(photon_bounding_sphere(scene)),
        disc_area_(std::numbers::pi * sphere_.radius_m * sphere_.radius_m),
        lattice_(*scene.medium, node, threads),
        period_(lateral_period_m) {
    if (period_ > 0.0) {
      if (!scene.surfaces.empty())
        throw Error("photon tracing: a laterally periodic slab has no surfaces");
      const BBox3 b = scene.medium->bounds();
      const double lateral = b.extent().x * b.extent().y;
      emission_share_ = lateral > 0 ? period_ * period_ / lateral : 0.0;
    }
  }

  // The powers used to share the photons out: the sun's beam through the
  // disc, the environment by kEnvironmentPilot pilot launches, the emission
  // lattice's estimate.
  PhotonSourcePowers estimate(const PhotonTracingSettings& settings,
                              std::uint64_t stream_base) const {
    PhotonSourcePowers est;
    const bool sun = scene_.sun.enabled && settings.sun_photons;
    if (sun) est.sun_w_um = scene_.sun.irradiance(node_.wavelength_um) * disc_area_;
    double sum = 0;
    MediumPoint scratch;
    for (int i = 0; i < kEnvironmentPilot; ++i) {
      Rng rng(settings.seed, stream_base + (1ull << 38) + static_cast<std::uint64_t>(i));
      sum += environment(rng, scratch, settings.surface_photons).power();
    }
    est.environment_w_um = sum / kEnvironmentPilot;
    est.emission_w_um = lattice_.estimated_power() * emission_share_;
    if (period_ > 0.0 && sun)  // through the P × P square of the top face
      est.sun_w_um =
          scene_.sun.irradiance(node_.wavelength_um) * scene_.sun.direction().z * period_ * period_;
    return est;
  }

  // Sun photon (power for one of n_sun): a direction over the disc, from
  // outside the sphere towards a point of the disc across the beam. Surfaces
  // on the way are met by the tracing (an unscattered photon stops there):
  // the line must not be dropped because the disc point itself is shaded
  // (e.g. below the ground), since the part of the line before the shading
  // surface can still cross the cloud.
  Launch sun(Rng& rng, long long n_sun) const {
    if (period_ > 0.0) return periodic_sun(rng, n_sun);
    Launch l;
    const Vec3 d = -sample_sun_direction(scene_.sun, rng);
    const Vec3 p = point_on_disc(sphere_.center, d, sphere_.radius_m, rng);
    l.power = scene_.sun.irradiance(node_.wavelength_um) * disc_area_ / n_sun;
    l.ray = Ray{p - d * (1.01 * sphere_.radius_m), d};
    return l;
  }

  // Environment photons of one line (each with the power for one line; the
  // caller divides by N_env): a direction d uniform over the sphere and a
  // point p on the disc of radius R across d pick the line x = p + s d. The
  // radiance travelling along it changes at every surface it crosses: each
  // stretch between two crossings carries what leaves the surface at its
  // start, or the sky's radiance where nothing is behind it. So the part of
  // the line in the medium's box is cut at the surfaces it crosses there, and
  // each piece launches its own photon, from the first surface behind the
  // piece's middle (the piece's start) or from beyond the sphere for the
  // sky; a piece inside a solid (Surface::encloses) carries no light.
  // (Before 2026-12-06 one photon came from the first surface behind p,
  // which missed every piece but p's: a line whose p lies below the ground
  // never carried the ground's light into a cloud above it, nor the sky's
  // into it before it reaches the ground. In a thin box lying on a black
  // ground in equilibrium with the sky, J read 16 % low; docs/physics.md.)
  // A line that misses the box keeps its one photon from behind p, which
  // meets no medium, so that without surfaces the launched power is the
  // environment's through the disc. Without `surfaces` the pieces whose light
  // leaves a surface launch nothing (PhotonTracingSettings::surface_photons).
  EnvironmentLaunches environment(Rng& rng, MediumPoint& scratch, bool surfaces) const {
    EnvironmentLaunches out;
    if (period_ > 0.0) {
      out.add(periodic_environment(rng));
      return out;
    }
    const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    const Vec3 p = point_on_disc(sphere_.center, d, sphere_.radius_m, rng);
    const double before_p = 1.01 * sphere_.radius_m;
    const Ray line{p - d * before_p, d};
    double t_in = 0.0, t_out = std::numeric_limits<double>::infinity();
    if (!scene_.medium->bounds().intersect(line, t_in, t_out) || !(t_out > t_in)) {
      if (auto l = from_behind(line, before_p, rng, scratch, surfaces)) out.add(*l);
      return out;
    }
    // Pieces shorter than this are dropped: a line through a corner of two
    // faces (a mesh's edge) crosses twice at one point.
    const double shortest = 1e-9 * (t_out - t_in);
    double start = t_in;
    // The crossing at `start`, once there is one: the first surface behind
    // every later piece, so that piece's light leaves it (no search back).
    std::optional<SurfaceHit> behind;
    while (out.count < EnvironmentLaunches::kMaxPieces) {
      SurfaceHit hit;
      const bool crosses = intersect_surfaces(scene_.surfaces, line, start, t_out, hit);
      const double end = crosses ? hit.t : t_out;
      // No light travels inside a solid (below the ground, inside a box).
      const double middle = 0.5 * (start + end);
      if (end - start > shortest && !inside_a_solid(scene_.surfaces, line.at(middle))) {
        if (behind) {
          if (surfaces) out.add(leaving(*behind, line.at(behind->t), d, rng, scratch));
        } else if (auto l = from_behind(line, middle, rng, scratch, surfaces)) {
          out.add(*l);
        }
      }
      if (!crosses) break;
      // Seen from beyond it, the crossing's normal faces the other way.
      behind = SurfaceHit{hit.t, -hit.normal, hit.surface};
      start = end;
    }
    return out;
  }

  // Emission photon (power for one of n_em): a point drawn from the lattice,
  // weighted by 4π σa B(T) over its density, a uniform direction.
  Launch emission(Rng& rng, MediumPoint& scratch, long long n_em) const {
    Launch l;
    double pdf = 0;
    const Vec3 x = lattice_.sample(rng, &pdf);
    scene_.medium->coefficients_of_samples(x, lambda_.sample0, lambda_.sample1, scratch);
    const double f =
        kFourPi * lambda_(scratch.sigma_a.data()) * node_.planck(scratch.temperature_k);
    l.power = f / (pdf * n_em);
    if (period_ > 0.0) l.power *= emission_share_;
    l.ray = Ray{x, sample_uniform_sphere(rng.uniform(), rng.uniform())};
    l.scattered = true;
    return l;
  }

 private:
  // The photon carrying the radiance that travels along `line` through its
  // point at parameter s: from the first surface behind that point, with the
  // surface's radiance (none without `surfaces`), or from the line's start
  // (beyond the sphere) with the sky's.
  std::optional<Launch> from_behind(const Ray& line, double s, Rng& rng, MediumPoint& scratch,
                                    bool surfaces) const {
    const Vec3& d = line.direction;
    SurfaceHit hit;
    const Ray back{line.at(s), -d};
    if (intersect_surfaces(scene_.surfaces, back, 0.0, std::numeric_limits<double>::infinity(),
                           hit)) {
      if (!surfaces) return std::nullopt;
      return leaving(hit, back.at(hit.t), d, rng, scratch);
    }
    Launch l;
    l.ray = line;
    l.from_sky = true;
    l.power = scene_.sky.radiance(-d, node_.wavelength_um) * kFourPi * disc_area_;
    return l;
  }

  // The photon carrying the radiance that leaves surface point x (`hit`,
  // its normal on the side d points to) along d.
  Launch leaving(const SurfaceHit& hit, const Vec3& x, const Vec3& d, Rng& rng,
                 MediumPoint& scratch) const {
    Launch l;
    l.ray = Ray{x + hit.normal * 1e-9, d};
    l.power = surface_radiance(scene_, hit, x, node_, rng, scratch) * kFourPi * disc_area_;
    return l;
  }

  // A point uniform on the period square at height z.
  Vec3 on_period_square(Rng& rng, double z) const {
    const double x = rng.uniform() * period_, y = rng.uniform() * period_;
    return {x, y, z};
  }

  // Periodic slab: sun photons through the P × P square of the top face; the
  // power through it is E cos θ_sun P² (cos of the drawn direction).
  Launch periodic_sun(Rng& rng, long long n_sun) const {
    Launch l;
    const Vec3 d = -sample_sun_direction(scene_.sun, rng);
    const double top = scene_.medium->bounds().hi.z;
    l.power = scene_.sun.irradiance(node_.wavelength_um) * -d.z * period_ * period_ / n_sun;
    l.ray = Ray{on_period_square(rng, top), d};
    return l;
  }

  // Periodic slab: sky photons through the top or the bottom face (each with
  // probability ½), cosine-distributed into the slab: the power through a
  // face is ∫ L |cos θ| dω P², which a cosine-distributed direction
  // estimates as π L(−d) P² (÷ N_env by the caller, × 2 for the face choice).
  Launch periodic_environment(Rng& rng) const {
    const bool from_top = rng.uniform() < 0.5;
    const BBox3 b = scene_.medium->bounds();
    Vec3 d = sample_cosine_hemisphere(rng.uniform(), rng.uniform());
    if (from_top) d.z = -d.z;
    Launch l;
    l.ray = Ray{on_period_square(rng, from_top ? b.hi.z : b.lo.z), d};
    l.power =
        2.0 * std::numbers::pi * scene_.sky.radiance(-d, node_.wavelength_um) * period_ * period_;
    return l;
  }

  const Scene& scene_;
  const SpectralNode& node_;
  SpectralLerp lambda_;
  BoundingSphere sphere_;
  double disc_area_;
  EmissionLattice lattice_;
  double period_ = 0.0;
  double emission_share_ = 1.0;  // of the emission lattice's power the photons carry
};

// Every process's chunks (c ≡ rank mod ranks) to every process.
void share_chunks(const ProcessGroup& processes, std::vector<ChunkRecord>& stored,
                  std::vector<std::array<double, 3>>& launched) {
  const auto rank = static_cast<std::size_t>(processes.rank()),
             ranks = static_cast<std::size_t>(processes.size());
  ByteWriter out;
  for (std::size_t c = rank; c < stored.size(); c += ranks) {
    out.put(launched[c]);
    out.put_vector(stored[c].photons);
    out.put_vector(stored[c].flights);
    out.put_vector(stored[c].deposits);
    out.put(stored[c].walks);
  }
  const std::vector<std::string> all = processes.all_gather(out.take());
  for (std::size_t r = 0; r < ranks; ++r) {
    if (r == rank) continue;
    ByteReader in(all[r]);
    for (std::size_t c = r; c < stored.size(); c += ranks) {
      launched[c] = in.get<std::array<double, 3>>();
      stored[c].photons = in.get_vector<Photon>();
      stored[c].flights = in.get_vector<PhotonFlight>();
      stored[c].deposits = in.get_vector<SurfaceDeposit>();
      stored[c].walks = in.get<PhotonWalks>();
    }
    OBSCURA_CHECK(in.done());
  }
}

}  // namespace

std::function<void(long long)> PhotonTracingProgress::on_traced() {
  if (!progress_) return {};
  return [this](long long photons) {
    std::lock_guard lock(mutex_);
    progress_(done_ += photons, total_);
  };
}

void PhotonTracingProgress::node_done(long long photons) {
  if (!progress_) return;
  std::lock_guard lock(mutex_);
  done_ = nodes_done_ += photons;
  progress_(done_, total_);
}

BoundingSphere photon_bounding_sphere(const Scene& scene) {
  if (!scene.medium) return {};
  const BBox3 b = scene.medium->bounds();
  return {b.center(), 0.5 * length(b.extent()) * (1.0 + 1e-9)};
}

TracedPhotons trace_photons(const Scene& scene, const SpectralNode& node, std::uint64_t stream_base,
                            const PhotonTracingSettings& settings) {
  TracedPhotons out;
  if (!scene.medium || settings.photons <= 0) return out;
  const PhotonSources sources(scene, node, settings.lateral_period_m, settings.threads);
  const SpectralLerp lambda = node.lerp();

  // Share the photons out by power.
  const PhotonSourcePowers& est = out.estimated = sources.estimate(settings, stream_base);
  const double total = est.total();
  if (!(total > 0)) return out;
  const long long n = settings.photons;
  const long long n_sun = std::llround(n * est.sun_w_um / total);
  const long long n_env = std::llround(n * est.environment_w_um / total);
  const long long n_em = std::max(0LL, n - n_sun - n_env);
  out.launched_count[kSun] = n_sun;
  out.launched_count[kEnvironment] = n_env;
  out.launched_count[kEmission] = est.emission_w_um > 0 ? n_em : 0;

  // Photon i draws from stream i: chunks of them in parallel (and among
  // processes), gathered in chunk order, so the result does not depend on the
  // thread or process count.
  const std::size_t chunks = static_cast<std::size_t>((n + kChunk - 1) / kChunk);
  std::vector<ChunkRecord> stored(chunks);
  std::vector<std::array<double, 3>> launched(chunks, {0, 0, 0});
  const ProcessGroup& processes = *settings.processes;
  const auto rank = static_cast<std::size_t>(processes.rank()),
             ranks = static_cast<std::size_t>(processes.size());
  const std::size_t own_chunks = chunks / ranks + (rank < chunks % ranks ? 1 : 0);
  // What is stored can outgrow what was checked before tracing (one photon
  // per launch is a lower bound: a photon stores each of its scatterings):
  // past the memory limit the remaining chunks are skipped, and every
  // process then learns whether any did so (below).
  const std::uint64_t limit = memory_limit_bytes();
  std::atomic<std::uint64_t> stored_bytes{0};
  std::atomic<bool> over{false};
  parallel_for(own_chunks, settings.threads, [&](std::size_t own) {
    throw_if_interrupted();
    if (over.load()) return;
    const std::size_t c = own * ranks + rank;
    MediumPoint scratch;
    const long long begin = static_cast<long long>(c) * kChunk, end = std::min(n, begin + kChunk);
    for (long long i = begin; i < end; ++i) {
      Rng rng(settings.seed, stream_base + static_cast<std::uint64_t>(i));
      Launch l;
      Source source;
      if (i < n_sun) {
        source = kSun;
        l = sources.sun(rng, n_sun);
      } else if (i < n_sun + n_env) {
        EnvironmentLaunches pieces = sources.environment(rng, scratch, settings.surface_photons);
        for (int k = 0; k < pieces.count; ++k) {
          Launch& piece = pieces.launch[static_cast<std::size_t>(k)];
          piece.power /= n_env;
          piece.store_first = settings.store_first_environment_scatter;
          launched[c][kEnvironment] += piece.power;
          if (piece.power > 0)
            trace_photon(scene, node, lambda, piece, settings, rng, scratch, stored[c]);
        }
        continue;
      } else {
        if (out.launched_count[kEmission] == 0) break;
        source = kEmission;
        l = sources.emission(rng, scratch, n_em);
      }
      launched[c][source] += l.power;
      if (l.power > 0) trace_photon(scene, node, lambda, l, settings, rng, scratch, stored[c]);
    }
    if (settings.on_traced) settings.on_traced(end - begin);
    const std::uint64_t bytes = stored[c].photons.size() * sizeof(Photon) +
                                stored[c].flights.size() * sizeof(PhotonFlight) +
                                stored[c].deposits.size() * sizeof(SurfaceDeposit);
    if ((stored_bytes += bytes) > limit) over = true;
  });
  // Every process the same verdict, so that none waits in a collective
  // another has left.
  bool any_over = over.load();
  std::uint64_t all_bytes = stored_bytes.load();
  if (ranks > 1) {
    ByteWriter mine;
    mine.put(stored_bytes.load());
    mine.put(static_cast<std::uint8_t>(any_over ? 1 : 0));
    all_bytes = 0;
    for (const std::string& bytes : processes.all_gather(mine.take())) {
      ByteReader in(bytes);
      all_bytes += in.get<std::uint64_t>();
      any_over = in.get<std::uint8_t>() != 0 || any_over;
    }
    any_over = any_over || all_bytes > limit;
  }
  if (any_over)
    throw InputError(
        "", settings.memory_field,
        fmt::format("the photons stored while tracing ({:.3g} GiB when tracing "
                    "stopped, at {} photons per spectral node) outgrew the memory "
                    "limit: {}; give fewer photons",
                    static_cast<double>(all_bytes) / (1ull << 30), n, memory_limit_text()));
  if (ranks > 1) share_chunks(processes, stored, launched);
  std::size_t total_photons = 0, total_flights = 0;
  for (const auto& s : stored) {
    total_photons += s.photons.size();
    total_flights += s.flights.size();
  }
  out.photons.reserve(total_photons);
  out.flights.reserve(total_flights);
  for (std::size_t c = 0; c < chunks; ++c) {
    out.photons.insert(out.photons.end(), stored[c].photons.begin(), stored[c].photons.end());
    out.flights.insert(out.flights.end(), stored[c].flights.begin(), stored[c].flights.end());
    out.deposits.insert(out.deposits.end(), stored[c].deposits.begin(), stored[c].deposits.end());
    out.launched.sun_w_um += launched[c][kSun];
    out.launched.environment_w_um += launched[c][kEnvironment];
    out.launched.emission_w_um += launched[c][kEmission];
    out.walks += stored[c].walks;
  }
  return out;
}

}  // namespace obscura
