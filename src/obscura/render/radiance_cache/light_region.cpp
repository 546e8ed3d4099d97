#include "obscura/render/radiance_cache/light_region.h"

#include <algorithm>
#include <cmath>

namespace obscura {
namespace {

// The inward normals of a pinhole camera's four side planes (through its
// position): a point x is in view when dot(n, x − position) ≥ 0 for all.
std::array<Vec3, 4> side_normals(const PinholeCamera& camera) {
  const double w = camera.width(), h = camera.height();
  const Vec3 corner[4] = {camera.generate_ray(0, 0).direction, camera.generate_ray(w, 0).direction,
                          camera.generate_ray(w, h).direction, camera.generate_ray(0, h).direction};
  const Vec3 axis = camera.generate_ray(0.5 * w, 0.5 * h).direction;
  std::array<Vec3, 4> n;
  for (int i = 0; i < 4; ++i) {
    n[i] = normalize(cross(corner[i], corner[(i + 1) % 4]));
    if (dot(n[i], axis) < 0) n[i] = -n[i];
  }
  return n;
}

}  // namespace

CellBox all_cells(const NodeLattice& lattice) {
  CellBox box;
  box.lo = {0, 0, 0};
  for (int a = 0; a < 3; ++a) box.hi[a] = lattice.dims()[a] - 2;
  return box;
}

CellBox cells_in_view(const NodeLattice& lattice, const std::vector<const PinholeCamera*>& cameras,
                      int margin_nodes) {
  if (lattice.periodic()) return all_cells(lattice);
  const double h = lattice.spacing_m();
  CellBox box;
  for (const PinholeCamera* camera : cameras) {
    const std::array<Vec3, 4> normal = side_normals(*camera);
    const Vec3 apex = camera->position();
    // Whether the cells from node `first` over `size` cells per axis may be
    // in view: not when all corners of their box, grown by half a spacing
    // against the planes' rounding, lie outside one side plane.
    const auto may_see = [&](const std::array<int, 3>& first, int size) {
      for (int i = 0; i < 4; ++i) {
        bool outside = true;
        for (int c = 0; c < 8 && outside; ++c) {
          Vec3 node;
          for (int a = 0; a < 3; ++a)
            node[a] = (c >> a & 1) ? (first[a] + size + 0.5) * h : (first[a] - 0.5) * h;
          outside = dot(normal[i], lattice.origin() + lattice.rotation() * node - apex) < 0.0;
        }
        if (outside) return false;
      }
      return true;
    };
    // Held blocks first, then the 2³-cell parts of those in view.
    constexpr int kPart = 2, kParts = NodeLattice::kBlock / kPart;
    for (std::size_t b = 0; b < lattice.block_count(); ++b) {
      const std::array<int, 3> first = lattice.block_first_node(b);
      if (!may_see(first, NodeLattice::kBlock)) continue;
      for (int p = 0; p < kParts * kParts * kParts; ++p) {
        const std::array<int, 3> part = {first[0] + kPart * (p % kParts),
                                         first[1] + kPart * (p / kParts % kParts),
                                         first[2] + kPart * (p / (kParts * kParts))};
        if (!may_see(part, kPart)) continue;
        CellBox grown;
        for (int a = 0; a < 3; ++a) {
          grown.lo[a] = part[a] - margin_nodes;
          grown.hi[a] = part[a] + kPart - 1 + margin_nodes;
        }
        box.add(grown);
      }
    }
  }
  if (box.empty()) return box;
  const CellBox all = all_cells(lattice);
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = std::max(box.lo[a], all.lo[a]);
    box.hi[a] = std::min(box.hi[a], all.hi[a]);
  }
  return box;
}

}  // namespace obscura
