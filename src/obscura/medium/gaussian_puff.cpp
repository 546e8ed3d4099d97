#include "obscura/medium/gaussian_puff.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "obscura/core/error.h"

namespace obscura {

void GaussianPuffSpec::validate() const {
  const std::string src = "gaussian puff";
  const std::size_t n = wavelengths_um.size();
  if (n == 0) throw InputError(src, "wavelengths_um", "needs at least one wavelength");
  if (peak_sigma_a.size() != n || peak_sigma_s.size() != n || g.size() != n)
    throw InputError(src, "peak_sigma_a/peak_sigma_s/g",
                     fmt::format("need one value per wavelength ({})", n));
  for (std::size_t k = 0; k < n; ++k) {
    if (!(peak_sigma_a[k] >= 0 && std::isfinite(peak_sigma_a[k])))
      throw InputError(src, "peak_sigma_a", "must be finite and >= 0 (1/m)");
    if (!(peak_sigma_s[k] >= 0 && std::isfinite(peak_sigma_s[k])))
      throw InputError(src, "peak_sigma_s", "must be finite and >= 0 (1/m)");
    if (!(g[k] > -1 && g[k] < 1)) throw InputError(src, "g", "must lie in (-1, 1)");
  }
  if (!(radius_m > 0 && std::isfinite(radius_m)))
    throw InputError(src, "radius_m", "must be > 0 m");
  if (!(extent_radii > 0)) throw InputError(src, "extent_radii", "must be > 0");
  if (resolution < 1) throw InputError(src, "resolution", "must be >= 1");
  if (!(ambient_temperature_k >= 0) || !(ambient_temperature_k + temperature_excess_k >= 0))
    throw InputError(src, "temperature", "temperatures must stay >= 0 K");
  if (!is_finite(center_m)) throw InputError(src, "center_m", "must be finite");
}

VoxelGrid make_gaussian_puff(const GaussianPuffSpec& spec) {
  spec.validate();
  GridPlacement placement;
  const double side = 2.0 * spec.extent_radii * spec.radius_m;
  placement.voxel_size_m = side / spec.resolution;
  placement.origin_m = spec.center_m - Vec3(side, side, side) * 0.5;
  const int n = spec.resolution;
  VoxelGrid grid({n, n, n}, placement, spec.wavelengths_um, "gaussian puff");
  const double inv_two_s2 = 1.0 / (2.0 * spec.radius_m * spec.radius_m);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 p = placement.index_to_world(Vec3(i, j, k));
        const Vec3 d = p - spec.center_m;
        const double rho = std::exp(-dot(d, d) * inv_two_s2);
        const std::size_t v = grid.index(i, j, k);
        for (int s = 0; s < grid.spectral_count(); ++s) {
          grid.sigma_a(s)[v] = static_cast<float>(spec.peak_sigma_a[s] * rho);
          grid.sigma_s(s)[v] = static_cast<float>(spec.peak_sigma_s[s] * rho);
          grid.g(s)[v] = static_cast<float>(spec.g[s]);
        }
        grid.temperature()[v] =
            static_cast<float>(spec.ambient_temperature_k + spec.temperature_excess_k * rho);
      }
  return grid;
}

double gaussian_puff_line_integral(const GaussianPuffSpec& spec, const Ray& ray, double t0,
                                   double t1) {
  const double s = spec.radius_m;
  const Vec3 p = ray.origin - spec.center_m;
  const double b = dot(p, ray.direction);
  const double closest2 = std::max(0.0, dot(p, p) - b * b);
  const double k = s * std::numbers::sqrt2;
  return s * std::sqrt(std::numbers::pi / 2.0) * std::exp(-closest2 / (2.0 * s * s)) *
         (std::erf((t1 + b) / k) - std::erf((t0 + b) / k));
}

}  // namespace obscura
