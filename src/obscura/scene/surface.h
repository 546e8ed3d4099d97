#pragma once
// Opaque background surfaces for the emission–absorption renderer: an infinite
// ground plane and axis-aligned boxes. Each is grey: emissivity ε and
// temperature T, emitting ε B_λ(T) and reflecting (1 − ε) of the environment
// Lambertianly (Kirchhoff's law for an opaque surface).
#include <memory>
#include <string>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/ray.h"

namespace obscura {

struct SurfaceMaterial {
  double temperature_k = 0.0;
  double emissivity = 1.0;  // in [0, 1]
};

struct SurfaceHit {
  double t = 0.0;  // metres along the ray
  Vec3 normal;     // unit, facing the incoming ray
  int surface = -1;
};

class Surface {
 public:
  Surface(std::string name, SurfaceMaterial material)
      : name_(std::move(name)), material_(material) {}
  virtual ~Surface() = default;
  // Nearest hit with t in (t_min, t_max); on success writes `hit` (not hit.surface).
  virtual bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const = 0;
  const std::string& name() const { return name_; }
  const SurfaceMaterial& material() const { return material_; }

 private:
  std::string name_;
  SurfaceMaterial material_;
};

// The plane z = height_m, seen from either side.
class GroundPlane final : public Surface {
 public:
  GroundPlane(std::string name, SurfaceMaterial m, double height_m)
      : Surface(std::move(name), m), height_m_(height_m) {}
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const override;

 private:
  double height_m_;
};

class BoxSurface final : public Surface {
 public:
  BoxSurface(std::string name, SurfaceMaterial m, BBox3 box)
      : Surface(std::move(name), m), box_(box) {}
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const override;
  const BBox3& box() const { return box_; }

 private:
  BBox3 box_;
};

// Nearest hit over all surfaces; hit.surface is the index into `surfaces`.
bool intersect_surfaces(const std::vector<std::unique_ptr<Surface>>& surfaces, const Ray& ray,
                        double t_min, double t_max, SurfaceHit& hit);

}  // namespace obscura
