#include "obscura/render/radiance_cache/ground_light.h"

#include <cmath>

namespace obscura {

GroundLight::GroundLight(const Scene& scene, const std::vector<SurfaceDeposit>& deposits,
                         const Vec3& centre, double half_width_m)
    : x0_(centre.x - half_width_m),
      y0_(centre.y - half_width_m),
      cell_m_(2.0 * half_width_m / kCells),
      nodes_(static_cast<std::size_t>(kCells + 1) * (kCells + 1), 0.0) {
  for (const auto& s : scene.surfaces) ground_.push_back(s->is_terrain());
  const double area = cell_m_ * cell_m_;
  for (const SurfaceDeposit& d : deposits) {
    if (!covers(d.surface)) continue;
    const double u = (d.position_m[0] - x0_) / cell_m_, v = (d.position_m[1] - y0_) / cell_m_;
    if (!(u >= 0.0 && v >= 0.0 && u < kCells && v < kCells)) continue;
    const int i = static_cast<int>(u), j = static_cast<int>(v);
    const double fu = u - i, fv = v - j, e = d.power / area;
    const std::size_t n = static_cast<std::size_t>(j) * (kCells + 1) + i;
    nodes_[n] += (1 - fu) * (1 - fv) * e;
    nodes_[n + 1] += fu * (1 - fv) * e;
    nodes_[n + kCells + 1] += (1 - fu) * fv * e;
    nodes_[n + kCells + 2] += fu * fv * e;
  }
}

bool GroundLight::has_ground(const Scene& scene) {
  for (const auto& s : scene.surfaces)
    if (s->is_terrain()) return true;
  return false;
}

double GroundLight::irradiance(const Vec3& p) const {
  if (nodes_.empty()) return 0.0;
  const double u = (p.x - x0_) / cell_m_, v = (p.y - y0_) / cell_m_;
  if (!(u >= 0.0 && v >= 0.0 && u < kCells && v < kCells)) return 0.0;
  const int i = static_cast<int>(u), j = static_cast<int>(v);
  const double fu = u - i, fv = v - j;
  const std::size_t n = static_cast<std::size_t>(j) * (kCells + 1) + i;
  return (1 - fu) * (1 - fv) * nodes_[n] + fu * (1 - fv) * nodes_[n + 1] +
         (1 - fu) * fv * nodes_[n + kCells + 1] + fu * fv * nodes_[n + kCells + 2];
}

double GroundLight::total_power_w_um() const {
  double sum = 0.0;
  for (const double e : nodes_) sum += e;
  return sum * cell_m_ * cell_m_;
}

}  // namespace obscura
