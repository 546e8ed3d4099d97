#include "obscura/prep/dispersion/wind.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura {

double Wind::speed_at_m_s(double height_m) const {
  const double z = std::max(height_m, minimum_height_m);
  return speed_m_s * std::pow(z / reference_height_m, power_law_exponent);
}

Vec3 Wind::downwind_direction() const {
  // "From" θ (clockwise from north) points at the source of the wind; the air
  // moves the opposite way. North is +y and east is +x, so the from-vector is
  // (sin θ, cos θ) and the downwind vector its negative.
  const double theta = from_deg * std::numbers::pi / 180.0;
  return {-std::sin(theta), -std::cos(theta), 0.0};
}

Vec3 Wind::velocity_at_m_s(double height_m) const {
  return downwind_direction() * speed_at_m_s(height_m);
}

}  // namespace obscura
