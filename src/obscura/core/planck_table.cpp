#include "obscura/core/planck_table.h"

#include <cmath>

#include "obscura/core/planck.h"

namespace obscura {

PlanckTable::PlanckTable(double wavelength_um)
    : formula_(wavelength_um),
      t_min_k_(std::sqrt(kC2_umK / (0.1 * wavelength_um))),
      value_(kMaxTableTemperatureK + 1, 0.0),
      slope_(kMaxTableTemperatureK + 1, 0.0) {
  for (int t = 1; t <= kMaxTableTemperatureK; ++t) {
    const double b = planck_radiance(wavelength_um, t), d = planck_radiance_dT(wavelength_um, t);
    // Far in the Wien tail (c2/λT > ~700) both underflow or overflow: zero.
    value_[t] = std::isfinite(b) ? b : 0.0;
    slope_[t] = std::isfinite(d) && std::isfinite(b) ? d : 0.0;
  }
}

}  // namespace obscura
