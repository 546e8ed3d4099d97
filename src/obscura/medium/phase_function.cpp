#include "obscura/medium/phase_function.h"

#include <fmt/format.h>

#include "obscura/core/error.h"

namespace obscura {

HenyeyGreenstein::HenyeyGreenstein(double g) : g_(g) {
  if (!(std::abs(g) < 1.0))  // also rejects NaN
    throw Error(fmt::format("Henyey–Greenstein asymmetry g must satisfy |g| < 1, got {}", g));
}

double HenyeyGreenstein::cdf(double cos_theta) const {
  if (!(cos_theta > -1.0)) return 0.0;
  if (cos_theta >= 1.0) return 1.0;
  const double root_d = std::sqrt(denominator(cos_theta));
  return std::min(1.0, (1.0 - g_) * (1.0 + cos_theta) / (root_d * (1.0 + g_ + root_d)));
}

SquareSample HenyeyGreenstein::invert(const Vec3& incoming_direction,
                                      const Vec3& outgoing_direction) const {
  const Vec3 local = world_to_local(incoming_direction, outgoing_direction);
  return {cdf(local.z), sampling_detail::azimuth_fraction(local.x, local.y)};
}

}  // namespace obscura
