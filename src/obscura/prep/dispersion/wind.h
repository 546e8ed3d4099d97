#pragma once
// A steady, horizontally uniform wind with a power-law profile in height
// (docs/domain.md §3.6): u(z) = u_ref (z / z_ref)^p.
//
// World axes are x east, y north, z up (z = 0 is the ground). The direction is
// the meteorological one: the direction the wind blows FROM, in degrees
// clockwise from north, so 0 = from the north (blowing towards −y),
// 90 = from the east (blowing towards −x), 270 = from the west (towards +x).
#include "obscura/core/vec3.h"

namespace obscura {

struct Wind {
  double speed_m_s = 3.0;            // u_ref at reference_height_m (> 0)
  double from_deg = 270.0;           // meteorological "from" direction
  double reference_height_m = 10.0;  // z_ref, where speed_m_s is measured (> 0)
  double power_law_exponent = 0.15;  // p (>= 0; 0: uniform in height)
  // Heights below this use the speed at this height: the power law gives
  // u(0) = 0, which would leave a ground release in place forever.
  // GasDispersion.jl's Gaussian puff takes the same floor (h_min = 1 m).
  double minimum_height_m = 1.0;

  // u(max(z, minimum_height_m)) in m/s.
  double speed_at_m_s(double height_m) const;
  // Unit horizontal vector the wind blows towards: (−sin θ, −cos θ, 0).
  Vec3 downwind_direction() const;
  // Velocity vector at a height: speed_at_m_s(z) · downwind_direction().
  Vec3 velocity_at_m_s(double height_m) const;
};

}  // namespace obscura
