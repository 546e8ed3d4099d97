#pragma once
// Pass 1 of volume photon mapping (Jensen & Christensen 1998; the source
// paper's method): photons are emitted from every light source in proportion
// to its power, traced through the cloud by delta tracking, continued at each
// real collision with probability Λ = σs/σt (Russian roulette with the
// scattering albedo, so a photon's power never changes; or, with
// absorb_by_weight, at their power times Λ) in a direction drawn from the HG
// phase function, and stored at scattering events. One set of photons per
// spectral node (the medium's coefficients depend on wavelength).
//
// Sources (docs/physics.md, "Volume photon mapping"), all for a node at λ:
//  * the sun: directions uniform over its disc, start points uniform on a disc
//    of the medium's bounding-sphere radius R across the beam; each photon
//    carries E_λ π R² / N_sun;
//  * the environment (sky and surfaces): a direction d uniform over the
//    sphere and a point p on the disc of radius R across d pick a line; the
//    line's part in the medium's box is cut at the surfaces it crosses, and
//    each piece launches a photon from the first surface behind it (with
//    that surface's radiance, render/direct_lighting.h) or from the sky,
//    carrying L π R² 4π / N_env;
//  * volume emission 4π σa B(T): points drawn from a lattice of cells over the
//    medium's box by the emission at each cell's centre (plus a defensive 1 %
//    of the mean, so every cell can be drawn), uniform within the cell,
//    directions uniform; each photon carries f(x)/(pdf(x) N_em), unbiased for
//    the continuous field.
//
// Which collisions are stored: with `store_first_scatter` false (the hybrid
// form), sun and environment photons are stored only after they have
// scattered once — the ray marcher computes their single scattering with
// shadow rays — and emission photons from their first scattering on. With it
// true (the paper's pure form) every scattering event is stored.
//
// At a surface, photons that have scattered (and all emission photons)
// reflect with probability 1 − ε into a cosine-distributed direction; sun and
// environment photons that have not scattered stop there, because their
// reflection is already part of the surface radiance the environment source
// uses.
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"
#include "obscura/render/photon_map/photon.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

struct PhotonTracingSettings {
  long long photons = 200000;  // launched per spectral node, all sources together
  bool store_first_scatter = false;
  // Store environment photons from their first scattering on even when
  // store_first_scatter is false: only the sun's single scattering is
  // computed apart (the radiance cache).
  bool store_first_environment_scatter = false;
  // > 0: the medium is a laterally infinite, laterally homogeneous slab with
  // no surfaces, and photons represent one period P × P of it: sun photons
  // enter through a P × P square of its top face, environment photons
  // through that square of its top or bottom face (cosine-distributed),
  // emission photons carry the share P²/(the box's lateral area) of their
  // power. Positions are stored unwrapped; the user wraps them (m).
  double lateral_period_m = 0.0;
  // Called with each chunk's photon count as it is traced, from any thread
  // (progress displays; an exception it throws stops the tracing).
  std::function<void(long long photons)> on_traced;
  std::uint64_t seed = 1;
  int threads = 0;
  int max_scatterings = 10000;  // safety net; roulette ends photons long before
  // The processes sharing the work (core/process_group.h): each traces the
  // chunks of photons whose index modulo their count is its rank, and every
  // process receives every chunk, in chunk order, so the photons are the same
  // bits for any number of processes. Called by every process together.
  const ProcessGroup* processes = &single_process();
  // The setting that asks for the photons, for the message when what is
  // stored while tracing outgrows the memory limit (core/memory_limit.h).
  std::string memory_field = "render/photon_map/photons";
  // Keep the flights that end in the collisions that would be stored (and
  // those of such photons that leave the medium or meet a surface), instead
  // of the stored photons: TracedPhotons::flights, photons left empty.
  bool flights = false;
  // At a real collision multiply the power by the albedo Λ (Russian roulette
  // below half the launch power) instead of ending the photon with
  // probability 1 − Λ at unchanged power: more, weaker flights, less noise
  // per photon where the albedo is high (the radiance cache's choice).
  bool absorb_by_weight = false;
  // Also keep TracedPhotons::deposits: the light the surfaces' own radiance
  // (render/background.h, which sees the sky as if no cloud were there)
  // leaves out: scattered photons arriving at a surface, and minus the
  // power a sky photon's first collision took from its straight line to a
  // surface (the radiance cache's ground light).
  bool surface_deposits = false;
  // Launch the sun's photons. Off where none could add to what is kept: in a
  // medium that does not scatter an unscattered sun photon is stored
  // nowhere and deposits nothing (its light on surfaces is in their own
  // radiance), so the others take its share of the count (the radiance
  // cache's nodes where σs = 0).
  bool sun_photons = true;
  // Launch the environment's photons whose light leaves a surface (the
  // pieces of a line that start at one). Off likewise where the medium does
  // not scatter: such a photon is absorbed at its first collision or goes
  // on unscattered, and deposits nothing; the sky's pieces, whose first
  // collision takes their light off the ground beyond, stay.
  bool surface_photons = true;
};

// Spectral powers (W µm⁻¹) per source kind.
struct PhotonSourcePowers {
  double sun_w_um = 0, environment_w_um = 0, emission_w_um = 0;
  double total() const { return sun_w_um + environment_w_um + emission_w_um; }
};

struct TracedPhotons {
  std::vector<Photon> photons;              // stored at scattering events
  std::vector<PhotonFlight> flights;        // with settings.flights: the flights instead
  std::vector<SurfaceDeposit> deposits;     // with settings.surface_deposits
  PhotonSourcePowers launched;              // Σ of the launched photons' powers per source
  PhotonSourcePowers estimated;             // the powers used to share the photons out
  long long launched_count[3] = {0, 0, 0};  // sun, environment, emission
  PhotonWalks walks;                        // render/integrator.h
};

// The progress of a frame's photon tracing over its spectral nodes, for a
// PreparationProgress: each chunk as it is traced (on_traced, for
// PhotonTracingSettings::on_traced), then a node's photons all at once when
// it is done (node_done; one whose sources have no power traces none),
// reported in increasing order whichever thread traced the chunk.
class PhotonTracingProgress {
 public:
  PhotonTracingProgress(PreparationProgress progress, long long total)
      : progress_(std::move(progress)), total_(total) {}
  // Empty without a progress to report to.
  std::function<void(long long photons)> on_traced();
  void node_done(long long photons);

 private:
  PreparationProgress progress_;
  long long total_ = 0, nodes_done_ = 0, done_ = 0;
  std::mutex mutex_;
};

// Throws InputError naming settings.memory_field when the photons (or
// flights) stored, on all processes together, outgrow the memory limit: the
// tracing stops at the next chunk, and every process throws alike.
TracedPhotons trace_photons(const Scene& scene, const SpectralNode& node, std::uint64_t stream_base,
                            const PhotonTracingSettings& settings);

// The bounding sphere photons enter through: centre and radius (m) of the
// medium's box; zero radius when the scene has no medium.
struct BoundingSphere {
  Vec3 center;
  double radius_m = 0;
};
BoundingSphere photon_bounding_sphere(const Scene& scene);

}  // namespace obscura
