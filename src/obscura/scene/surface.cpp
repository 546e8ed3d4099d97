#include "obscura/scene/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace obscura {

SurfaceMaterial::SurfaceMaterial(double temperature, double grey_emissivity,
                                 const std::vector<std::pair<double, double>>& table)
    : temperature_k(temperature), emissivity(grey_emissivity) {
  if (table.empty()) return;
  std::vector<double> wavelengths, values;
  for (const auto& [w, e] : table) {
    wavelengths.push_back(w);
    values.push_back(e);
  }
  emissivity_table = TabulatedSpectrum(std::move(wavelengths), std::move(values));
}

bool Surface::encloses(const Vec3& p) const {
  if (!is_terrain()) return false;
  SurfaceHit hit;
  return intersect(Ray{p, Vec3(0, 0, 1)}, 0.0, std::numeric_limits<double>::infinity(), hit);
}

bool BoxSurface::encloses(const Vec3& p) const {
  return p.x > box_.lo.x && p.x < box_.hi.x && p.y > box_.lo.y && p.y < box_.hi.y &&
         p.z > box_.lo.z && p.z < box_.hi.z;
}

bool inside_a_solid(const std::vector<std::unique_ptr<Surface>>& surfaces, const Vec3& p) {
  for (const auto& s : surfaces)
    if (s->encloses(p)) return true;
  return false;
}

bool GroundPlane::intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
  if (ray.direction.z == 0.0) return false;
  const double t = (height_m_ - ray.origin.z) / ray.direction.z;
  if (!(t > t_min && t < t_max)) return false;
  hit.t = t;
  hit.normal = Vec3(0, 0, ray.direction.z < 0 ? 1.0 : -1.0);
  return true;
}

bool BoxSurface::intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
  double t0 = t_min, t1 = t_max;
  if (!box_.intersect(ray, t0, t1)) return false;
  // Entering hit if the origin is outside, else the exit (seen from inside).
  const double t = (t0 > t_min) ? t0 : t1;
  if (!(t > t_min && t < t_max)) return false;
  const Vec3 p = ray.at(t);
  // The face whose plane the point lies closest to gives the normal.
  int axis = 0;
  double best = INFINITY;
  double sign = 1;
  for (int a = 0; a < 3; ++a) {
    const double dlo = std::abs(p[a] - box_.lo[a]);
    const double dhi = std::abs(p[a] - box_.hi[a]);
    if (dlo < best) {
      best = dlo;
      axis = a;
      sign = -1;
    }
    if (dhi < best) {
      best = dhi;
      axis = a;
      sign = 1;
    }
  }
  Vec3 n(0, 0, 0);
  n[axis] = sign;
  if (dot(n, ray.direction) > 0) n = -n;
  hit.t = t;
  hit.normal = n;
  return true;
}

bool intersect_surfaces(const std::vector<std::unique_ptr<Surface>>& surfaces, const Ray& ray,
                        double t_min, double t_max, SurfaceHit& hit) {
  bool found = false;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    SurfaceHit h;
    if (surfaces[i]->intersect(ray, t_min, t_max, h)) {
      hit = h;
      hit.surface = static_cast<int>(i);
      t_max = h.t;
      found = true;
    }
  }
  return found;
}

}  // namespace obscura
