#pragma once
// A stored volume photon (Jensen & Christensen 1998, §3): where it was stored,
// which way it was travelling and the power it carries. One photon map holds
// the photons of one spectral node (the medium's coefficients depend on
// wavelength), so the power is a single number, not a spectrum.
//
// Layout (28 bytes, 4-byte aligned, no padding):
//   offset  0  float position_m[3]  world position, metres
//   offset 12  float direction[3]   unit direction of travel when stored
//   offset 24  float power          spectral power at the map's node, W µm⁻¹
// Floats, not doubles: millions of photons are stored per node and a float
// places a photon to ~1e-7 of its distance from the origin (0.1 mm at 1 km),
// far below any density-estimation radius. Queries compute distances in double
// from these floats (photon/photon_map.h). The struct is an aggregate so the
// tracer can write Photon{{x, y, z}, {dx, dy, dz}, power}.
#include <cstddef>
#include <cstdint>

#include "obscura/core/vec3.h"

namespace obscura {

struct Photon {
  float position_m[3];
  float direction[3];
  float power;  // W µm⁻¹ at the map's spectral node

  Vec3 position() const { return {position_m[0], position_m[1], position_m[2]}; }
  Vec3 dir() const { return {direction[0], direction[1], direction[2]}; }
};

// The layout above is what the memory figures (docs/photon-map.md) and any
// future file or GPU copy of a map rely on.
static_assert(sizeof(Photon) == 28, "Photon must stay 7 floats with no padding");
static_assert(alignof(Photon) == 4);
static_assert(offsetof(Photon, direction) == 12 && offsetof(Photon, power) == 24);

// A photon's free flight (the radiance cache's track-length estimate,
// render/radiance_cache/flight_splat.h): from `origin_m` along `direction` for
// `length_m` metres, to its next real collision or out of the medium,
// carrying `power`. Where a stored Photon samples σs L at a collision, the
// flight's whole track does (the same expectation, ∫ σs along it).
// Layout (32 bytes, no padding): origin[3], direction[3], length, power.
struct PhotonFlight {
  float origin_m[3];
  float direction[3];
  float length_m;
  float power;  // W µm⁻¹ at the spectral node

  Vec3 origin() const { return {origin_m[0], origin_m[1], origin_m[2]}; }
  Vec3 dir() const { return {direction[0], direction[1], direction[2]}; }
};

static_assert(sizeof(PhotonFlight) == 32, "PhotonFlight must stay 8 floats with no padding");

// Power a surface's own radiance leaves out when the cloud is not in it
// (render/photon_map/photon_tracing.h, surface_deposits): a photon arriving
// at the surface after scattering (power > 0), or the power a sky photon's
// first collision took from the straight line to the surface beyond it
// (power < 0), W µm⁻¹, at the point where it meets the surface.
struct SurfaceDeposit {
  float position_m[3];
  float power;
  std::int32_t surface;  // index into Scene::surfaces

  Vec3 position() const { return {position_m[0], position_m[1], position_m[2]}; }
};

static_assert(sizeof(SurfaceDeposit) == 20, "SurfaceDeposit must stay 5 words with no padding");

}  // namespace obscura
