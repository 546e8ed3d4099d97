#include "obscura/core/planck_table.h"

#include <cmath>
#include <vector>

#include "obscura/core/planck.h"

namespace obscura {

PlanckTable::PlanckTable(double wavelength_um)
    : formula_(wavelength_um),
      t_min_k_(std::sqrt(kC2_umK / (0.1 * wavelength_um))),
      cubic_(4 * static_cast<std::size_t>(kMaxTableTemperatureK), 0.0) {
  std::vector<double> value(kMaxTableTemperatureK + 1, 0.0), slope(kMaxTableTemperatureK + 1, 0.0);
  for (int t = 1; t <= kMaxTableTemperatureK; ++t) {
    const double b = planck_radiance(wavelength_um, t), d = planck_radiance_dT(wavelength_um, t);
    // Far in the Wien tail (c2/λT > ~700) both underflow or overflow: zero.
    value[t] = std::isfinite(b) ? b : 0.0;
    slope[t] = std::isfinite(d) && std::isfinite(b) ? d : 0.0;
  }
  for (int i = 0; i < kMaxTableTemperatureK; ++i) {
    const double b0 = value[i], b1 = value[i + 1], d0 = slope[i], d1 = slope[i + 1];
    double* c = cubic_.data() + 4 * static_cast<std::size_t>(i);
    c[0] = b0;
    c[1] = d0;
    c[2] = 3.0 * (b1 - b0) - 2.0 * d0 - d1;
    c[3] = 2.0 * (b0 - b1) + d0 + d1;
  }
}

}  // namespace obscura
