#include "obscura/medium/homogeneous_medium.h"

#include <fmt/format.h>

#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

HomogeneousMedium::HomogeneousMedium(BBox3 box, std::vector<double> wavelengths_um,
                                     std::vector<double> sigma_a, std::vector<double> sigma_s,
                                     std::vector<double> g, double temperature_k,
                                     const std::string& source)
    : box_(box), wavelengths_um_(std::move(wavelengths_um)) {
  const std::size_t n = wavelengths_um_.size();
  if (n == 0) throw InputError(source, "wavelengths_um", "needs at least one spectral sample");
  auto check_size = [&](const std::vector<double>& v, const char* name) {
    if (v.size() != n)
      throw InputError(source, name,
                       fmt::format("has {} values but there are {} wavelengths", v.size(), n));
  };
  check_size(sigma_a, "sigma_a");
  check_size(sigma_s, "sigma_s");
  check_size(g, "g");
  for (std::size_t k = 0; k < n; ++k) {
    if (!(std::isfinite(wavelengths_um_[k]) && wavelengths_um_[k] > 0) ||
        (k > 0 && !(wavelengths_um_[k] > wavelengths_um_[k - 1])))
      throw InputError(source, fmt::format("wavelengths_um[{}]", k),
                       "wavelengths must be finite, > 0 µm and strictly increasing");
    if (!(std::isfinite(sigma_a[k]) && sigma_a[k] >= 0))
      throw InputError(source, fmt::format("sigma_a[{}]", k), "must be finite and >= 0 (1/m)");
    if (!(std::isfinite(sigma_s[k]) && sigma_s[k] >= 0))
      throw InputError(source, fmt::format("sigma_s[{}]", k), "must be finite and >= 0 (1/m)");
    if (!(g[k] > -1 && g[k] < 1))
      throw InputError(source, fmt::format("g[{}]", k), "must lie in (-1, 1)");
  }
  if (!(std::isfinite(temperature_k) && temperature_k >= 0))
    throw InputError(source, "temperature", "must be finite and >= 0 K");
  if (box.empty() || !is_finite(box.lo) || !is_finite(box.hi))
    throw InputError(source, "box", "must be a finite, non-empty box");
  values_.sigma_a = std::move(sigma_a);
  values_.sigma_s = std::move(sigma_s);
  values_.g = std::move(g);
  values_.temperature_k = temperature_k;
  cubics_.resize(2 * n);
  sigma_t_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    cubics_[k] = Cubic::constant(values_.sigma_a[k]);
    cubics_[n + k] = Cubic::constant(values_.sigma_s[k]);
    sigma_t_[k] = values_.sigma_a[k] + values_.sigma_s[k];
  }
}

void HomogeneousMedium::coefficients_at(const Vec3& p, MediumPoint& out) const {
  if (box_.contains(p)) {
    out = values_;
  } else {
    const std::size_t n = wavelengths_um_.size();
    out.sigma_a.assign(n, 0.0);
    out.sigma_s.assign(n, 0.0);
    out.g.assign(n, 0.0);
    out.temperature_k = 0.0;
  }
}

void HomogeneousMedium::trace_segments(const Ray& ray, double t_min, double t_max,
                                       const SegmentVisitor& visit) const {
  if (!box_.intersect(ray, t_min, t_max) || !(t_max > t_min)) return;
  const int n = static_cast<int>(wavelengths_um_.size());
  MediumComponent component;
  component.sigma_a = cubics_.data();
  component.sigma_s = cubics_.data() + n;
  component.temperature = Cubic::constant(values_.temperature_k);
  MediumSegment seg;
  seg.t_begin = t_min;
  seg.t_end = t_max;
  seg.spectral_count = n;
  seg.components = &component;
  seg.component_count = 1;
  visit(seg);
}

void HomogeneousMedium::trace_majorants(const Ray& ray, double t_min, double t_max,
                                        const MajorantVisitor& visit) const {
  if (!box_.intersect(ray, t_min, t_max) || !(t_max > t_min)) return;
  // Constant: σt bounds itself from both sides.
  visit(MajorantSegment{t_min, t_max, sigma_t_.data(), static_cast<int>(sigma_t_.size()),
                        sigma_t_.data()});
}

}  // namespace obscura
