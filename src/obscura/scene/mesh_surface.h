#pragma once
// An opaque triangle-mesh surface (one part of a vehicle, a heightfield
// ground) intersected through an Embree BVH.
//
// Precision. Embree works in single precision; scenes place sensors kilometres
// from their targets and the integrators leave a surface from a point lifted
// by only 1e-9 m along its normal. So Embree decides which triangle a ray
// crosses (watertight: a ray through a shared edge finds one of its
// triangles), and where it crosses it is decided in double precision:
//  * the BVH holds the vertices relative to the mesh's centre, and each ray is
//    first clipped to the mesh's box in double precision and its origin moved
//    along the ray to just before that box, so float coordinates never exceed
//    the mesh's own size;
//  * a filter on every candidate recomputes its distance as the distance
//    along the caller's ray to the triangle's plane, in double precision, and
//    rejects it unless it lies in (t_min, t_max). A ray leaving a triangle
//    (origin on its plane or 1e-9 m off it, moving away) meets that plane at
//    t <= 0 and never hits it again, at any range: no epsilon on tnear is
//    needed. Embree's own tnear/tfar are widened by a margin (1e-4 of the
//    mesh's size) so that they never cull a valid hit.
// The hit's t and normal are those of the triangle's plane in double
// precision. What float still decides is which side of an edge a ray passes
// within ~1e-7 of the mesh's size: such a ray may be given the neighbouring
// triangle, or miss a grazing one (tests/scene/mesh_surface_test.cpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "obscura/core/triangle_mesh.h"
#include "obscura/scene/surface.h"

struct RTCSceneTy;  // Embree's scene handle (embree3/rtcore_scene.h)

namespace obscura {

class MeshSurface final : public Surface {
 public:
  // Builds the BVH over every triangle of `mesh` (all parts) that has a
  // non-zero area; throws Error if none has, or if Embree fails.
  MeshSurface(std::string name, SurfaceMaterial material, const TriangleMesh& mesh);
  ~MeshSurface() override;
  MeshSurface(const MeshSurface&) = delete;
  MeshSurface& operator=(const MeshSurface&) = delete;

  // Nearest hit with t in (max(t_min, 0), t_max); thread-safe.
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const override;

  const BBox3& bounds() const { return bounds_; }
  std::size_t triangle_count() const { return triangles_.size(); }

  // Distance along `ray` to the plane of BVH triangle `index` (Embree's
  // primitive id), in double precision: ±inf or NaN when parallel to it.
  double plane_distance(std::size_t index, const Ray& ray) const;

 private:
  // (b − a) × (c − a) of BVH triangle `index`: its normal, not normalised.
  Vec3 area_normal(std::size_t index) const;
  // Distance along `ray` to the plane through vertex `a` with normal `n`.
  static double plane_distance(const Vec3& a, const Vec3& n, const Ray& ray) {
    return dot(n, a - ray.origin) / dot(n, ray.direction);
  }

  struct SceneRelease {
    void operator()(RTCSceneTy* scene) const;
  };
  std::vector<Vec3> vertices_;                           // m, as given
  std::vector<std::array<std::uint32_t, 3>> triangles_;  // those with an area, in BVH order
  BBox3 bounds_;
  Vec3 centre_;
  double margin_ = 0;    // m: how far the float ray starts before the box, and Embree's slack
  BBox3 padded_bounds_;  // bounds_ grown by margin_ on every side: where rays are clipped
  std::unique_ptr<RTCSceneTy, SceneRelease> scene_;
};

}  // namespace obscura
