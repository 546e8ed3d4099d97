#include "obscura/medium/medium.h"

namespace obscura {

std::vector<double> Medium::optical_depth(const Ray& ray, double t_min, double t_max) const {
  std::vector<double> tau(wavelengths_um().size(), 0.0);
  trace_segments(ray, t_min, t_max, [&](const MediumSegment& seg) {
    const double h = seg.t_end - seg.t_begin;
    for (int k = 0; k < seg.spectral_count; ++k)
      tau[k] += seg.sigma_a[k].integral(h) + seg.sigma_s[k].integral(h);
    return true;
  });
  return tau;
}

}  // namespace obscura
