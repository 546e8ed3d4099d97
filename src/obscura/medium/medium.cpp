#include "obscura/medium/medium.h"

namespace obscura {

void Medium::add_optical_depth(const Ray& ray, double t_min, double t_max, double* tau) const {
  trace_segments(ray, t_min, t_max, [&](const MediumSegment& seg) {
    const double h = seg.t_end - seg.t_begin;
    for (int c = 0; c < seg.component_count; ++c)
      for (int k = 0; k < seg.spectral_count; ++k)
        tau[k] +=
            seg.components[c].sigma_a[k].integral(h) + seg.components[c].sigma_s[k].integral(h);
    return true;
  });
}

std::vector<double> Medium::optical_depth(const Ray& ray, double t_min, double t_max) const {
  std::vector<double> tau(wavelengths_um().size(), 0.0);
  add_optical_depth(ray, t_min, t_max, tau.data());
  return tau;
}

}  // namespace obscura
