#pragma once
// Opaque surfaces: an infinite ground plane and axis-aligned boxes here,
// triangle meshes elsewhere. Each has a temperature T and an emissivity ε(λ)
// (one value, or a table over wavelength), emits ε(λ) B_λ(T) and reflects
// (1 − ε(λ)) of the light falling on it Lambertianly (Kirchhoff's law for an
// opaque surface: the Lambertian reflectance is 1 − ε).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/ray.h"
#include "obscura/core/tabulated_spectrum.h"

namespace obscura {

struct SurfaceMaterial {
  SurfaceMaterial() = default;
  // `table`: (wavelength µm, ε) points, as emissivity_table below.
  SurfaceMaterial(double temperature, double grey_emissivity,
                  const std::vector<std::pair<double, double>>& table = {});

  double temperature_k = 0.0;
  double emissivity = 1.0;  // in [0, 1]; used where emissivity_table is empty
  // ε(λ), wavelengths strictly increasing, ε in [0, 1]: linear between
  // points, held constant beyond the first and the last.
  TabulatedSpectrum emissivity_table;

  double emissivity_at(double wavelength_um) const {
    return emissivity_table.empty() ? emissivity : emissivity_table(wavelength_um);
  }
  double reflectance_at(double wavelength_um) const { return 1.0 - emissivity_at(wavelength_um); }
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
  // Part of the target: its pixels form the target mask of screening metrics.
  bool is_target() const { return target_; }
  void set_target(bool target) { target_ = target; }
  // Ground: the graph of a height z(x, y), at most one point of it above
  // each (x, y) (a ground plane, a heightfield), which the radiance cache's
  // map of the cloud's light on the ground covers
  // (render/radiance_cache/ground_light.h).
  bool is_terrain() const { return terrain_; }
  void set_terrain(bool terrain) { terrain_ = terrain; }
  // Whether p lies inside the solid this surface bounds, where no light
  // travels: below a terrain (a vertical ray up from p meets it), inside a
  // box. False where that is not known (a mesh's inside).
  virtual bool encloses(const Vec3& p) const;

 private:
  std::string name_;
  SurfaceMaterial material_;
  bool target_ = false;
  bool terrain_ = false;
};

// The plane z = height_m, seen from either side.
class GroundPlane final : public Surface {
 public:
  GroundPlane(std::string name, SurfaceMaterial m, double height_m)
      : Surface(std::move(name), m), height_m_(height_m) {
    set_terrain(true);
  }
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const override;

 private:
  double height_m_;
};

class BoxSurface final : public Surface {
 public:
  BoxSurface(std::string name, SurfaceMaterial m, BBox3 box)
      : Surface(std::move(name), m), box_(box) {}
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const override;
  bool encloses(const Vec3& p) const override;
  const BBox3& box() const { return box_; }

 private:
  BBox3 box_;
};

// Whether p lies inside the solid of any of `surfaces` (Surface::encloses).
bool inside_a_solid(const std::vector<std::unique_ptr<Surface>>& surfaces, const Vec3& p);

// Nearest hit over all surfaces; hit.surface is the index into `surfaces`.
bool intersect_surfaces(const std::vector<std::unique_ptr<Surface>>& surfaces, const Ray& ray,
                        double t_min, double t_max, SurfaceHit& hit);

}  // namespace obscura
