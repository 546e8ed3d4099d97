#pragma once
// The cloud's light on the ground (terrain surfaces: a ground plane, a
// heightfield; Surface::is_terrain) for the radiance cache: what a surface's
// own radiance (render/background.h) leaves out, since it sees the sky as if
// no cloud were there. From pass 1's surface deposits (photon_tracing.h):
// scattered photons arriving at the ground (sun, sky and emission light the
// cloud sends down) add their power, and the power a sky photon's first
// collision took from its straight line to the ground (the cloud's shadow on
// the sky light) is taken away. Their sum per horizontal area is the
// irradiance the surface misses, ΔE (W m⁻² µm⁻¹), and a Lambertian ground of
// reflectance ρ sends ρ ΔE n_z / π more towards the camera, n_z the vertical
// component of its unit normal (a sloped facet over a horizontal area A has
// the area A / n_z; docs/physics.md, "The cloud's light on the ground").
//
// The map is a square of kCells² cells across the photons' bounding disc
// (twice its radius each side: the light falls beyond the cloud), each
// deposit shared among the four nearest nodes by bilinear weights and read
// back bilinearly, so the total deposited inside the square is kept exactly.
// Deterministic: the deposits are added in their stored order.
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/render/photon_map/photon.h"
#include "obscura/scene/scene.h"

namespace obscura {

class GroundLight {
 public:
  static constexpr int kCells = 64;

  GroundLight() = default;
  // From the deposits on the terrain surfaces of `scene`, over the square of
  // half-width `half_width_m` around `centre` (x and y).
  GroundLight(const Scene& scene, const std::vector<SurfaceDeposit>& deposits, const Vec3& centre,
              double half_width_m);

  // Whether `scene` has ground such a map covers (a terrain surface).
  static bool has_ground(const Scene& scene);

  // ΔE per horizontal area at ground point p (0 outside the square or
  // without a map), W m⁻² µm⁻¹.
  double irradiance(const Vec3& p) const;
  // Whether surface `surface` of the scene is ground the map covers.
  bool covers(int surface) const {
    return surface >= 0 && surface < static_cast<int>(ground_.size()) && ground_[surface];
  }
  // Σ ΔE × node area: the power kept (W µm⁻¹).
  double total_power_w_um() const;

 private:
  double x0_ = 0.0, y0_ = 0.0, cell_m_ = 1.0;
  std::vector<double> nodes_;  // (kCells + 1)², x fastest, W m⁻² µm⁻¹
  std::vector<bool> ground_;   // per scene surface: terrain
};

}  // namespace obscura
