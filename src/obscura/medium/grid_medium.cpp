#include "obscura/medium/grid_medium.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "obscura/medium/lattice_walker.h"

namespace obscura {

GridMedium::GridMedium(std::shared_ptr<const VoxelGrid> grid, int block_size)
    : grid_(std::move(grid)), majorants_(*grid_, block_size), bounds_(grid_->world_bounds()) {}

namespace {

// Corner voxel indices and the fractional position inside the reconstruction
// cell that holds index coordinate u along one axis of n voxels.
struct AxisLerp {
  int i0, i1;
  double f;
};
inline AxisLerp axis_lerp(double u, int n) {
  const double c = std::floor(u);
  const int ci = static_cast<int>(c);
  return {std::clamp(ci, 0, n - 1), std::clamp(ci + 1, 0, n - 1), u - c};
}

// The ray in "cell space" w = index + 1, where reconstruction cell c' spans
// [c', c'+1] and the grid occupies [½, n + ½]; t stays the world distance in
// metres. Clips [t_min, t_max] to the grid; false if the ray misses it.
bool to_cell_space(const VoxelGrid& g, const Ray& ray, double& t_min, double& t_max,
                   Ray& cell_ray) {
  const GridDims& d = g.dims();
  cell_ray = Ray{g.placement().world_to_index(ray.origin) + Vec3(1, 1, 1),
                 g.placement().world_to_index_direction(ray.direction)};
  const BBox3 domain(Vec3(0.5, 0.5, 0.5), Vec3(d.nx + 0.5, d.ny + 0.5, d.nz + 0.5));
  return domain.intersect(cell_ray, t_min, t_max);
}

// Grid indices of the corners of the cell [c0, c1] (per axis).
void cell_corner_indices(const VoxelGrid& g, const std::array<int, 3>& c0,
                         const std::array<int, 3>& c1, std::array<std::size_t, 8>& corner_index) {
  for (int corner = 0; corner < 8; ++corner) {
    corner_index[corner] = g.index((corner & 1) ? c1[0] : c0[0], (corner & 2) ? c1[1] : c0[1],
                                   (corner & 4) ? c1[2] : c0[2]);
  }
}

// Whether any corner has σa or σs ≠ 0 at any spectral sample (else the cell
// is clear and gives no segment).
bool any_extinction(const VoxelGrid& g, int ns, const std::array<std::size_t, 8>& corner_index) {
  bool any = false;
  for (int s = 0; s < ns && !any; ++s)
    for (int corner = 0; corner < 8; ++corner)
      if (g.sigma_a(s)[corner_index[corner]] != 0.0f ||
          g.sigma_s(s)[corner_index[corner]] != 0.0f) {
        any = true;
        break;
      }
  return any;
}

// Each corner's trilinear weight is a product of three linear factors in s,
// hence a cubic; the field is the corner values' combination of them.
void corner_weight_cubics(const std::array<double, 3>& alpha, const std::array<double, 3>& beta,
                          std::array<Cubic, 8>& basis) {
  for (int corner = 0; corner < 8; ++corner) {
    double a1, b1, a2, b2, a3, b3;
    if (corner & 1) {
      a1 = alpha[0];
      b1 = beta[0];
    } else {
      a1 = 1 - alpha[0];
      b1 = -beta[0];
    }
    if (corner & 2) {
      a2 = alpha[1];
      b2 = beta[1];
    } else {
      a2 = 1 - alpha[1];
      b2 = -beta[1];
    }
    if (corner & 4) {
      a3 = alpha[2];
      b3 = beta[2];
    } else {
      a3 = 1 - alpha[2];
      b3 = -beta[2];
    }
    basis[corner].c[0] = a1 * a2 * a3;
    basis[corner].c[1] = b1 * a2 * a3 + a1 * b2 * a3 + a1 * a2 * b3;
    basis[corner].c[2] = b1 * b2 * a3 + b1 * a2 * b3 + a1 * b2 * b3;
    basis[corner].c[3] = b1 * b2 * b3;
  }
}

}  // namespace

void GridMedium::coefficients_at(const Vec3& p, MediumPoint& out) const {
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();
  out.sigma_a.assign(ns, 0.0);
  out.sigma_s.assign(ns, 0.0);
  out.g.assign(ns, 0.0);
  out.temperature_k = 0.0;
  const Vec3 u = g.placement().world_to_index(p);
  const GridDims& d = g.dims();
  if (!(u.x >= -0.5 && u.x <= d.nx - 0.5 && u.y >= -0.5 && u.y <= d.ny - 0.5 && u.z >= -0.5 &&
        u.z <= d.nz - 0.5))
    return;
  const AxisLerp ax = axis_lerp(u.x, d.nx), ay = axis_lerp(u.y, d.ny), az = axis_lerp(u.z, d.nz);
  std::array<std::size_t, 8> idx;
  std::array<double, 8> w;
  for (int c = 0; c < 8; ++c) {
    idx[c] = g.index((c & 1) ? ax.i1 : ax.i0, (c & 2) ? ay.i1 : ay.i0, (c & 4) ? az.i1 : az.i0);
    w[c] = ((c & 1) ? ax.f : 1 - ax.f) * ((c & 2) ? ay.f : 1 - ay.f) * ((c & 4) ? az.f : 1 - az.f);
  }
  for (int s = 0; s < ns; ++s) {
    double sa = 0, ss = 0, gs = 0;
    for (int c = 0; c < 8; ++c) {
      sa += w[c] * g.sigma_a(s)[idx[c]];
      const double ssc = w[c] * g.sigma_s(s)[idx[c]];
      ss += ssc;
      gs += ssc * g.g(s)[idx[c]];
    }
    out.sigma_a[s] = sa;
    out.sigma_s[s] = ss;
    // g weighted by scattering, so that mixing clear and scattering voxels
    // keeps the scatterers' phase function.
    out.g[s] = ss > 0 ? gs / ss : 0.0;
  }
  double t = 0;
  for (int c = 0; c < 8; ++c) t += w[c] * g.temperature()[idx[c]];
  out.temperature_k = t;
}

void GridMedium::trace_segments(const Ray& ray, double t_min, double t_max,
                                const SegmentVisitor& visit) const {
  const VoxelGrid& g = *grid_;
  const GridDims& d = g.dims();
  const int ns = g.spectral_count();
  const std::array<int, 3> n = {d.nx, d.ny, d.nz};
  Ray cell_ray;
  if (!to_cell_space(g, ray, t_min, t_max, cell_ray)) return;
  const Vec3& o = cell_ray.origin;
  const Vec3& dir = cell_ray.direction;

  std::vector<Cubic> cubics(2 * static_cast<std::size_t>(ns));
  Cubic* sig_a = cubics.data();
  Cubic* sig_s = cubics.data() + ns;
  MediumComponent component;
  component.sigma_a = sig_a;
  component.sigma_s = sig_s;
  MediumSegment seg;
  seg.spectral_count = ns;
  seg.components = &component;
  seg.component_count = 1;
  double previous_end = -1.0;

  const int bsize = majorants_.block_size();
  const auto& bd = majorants_.block_dims();
  LatticeWalker blocks(o, dir, t_min, t_max, bsize, {0, 0, 0}, {bd[0] - 1, bd[1] - 1, bd[2] - 1});
  std::array<int, 3> block;
  double tb0, tb1;
  std::array<Cubic, 8> basis;
  std::array<std::size_t, 8> corner_index;
  while (blocks.next(block, tb0, tb1)) {
    if (majorants_.max_majorant(block[0], block[1], block[2]) <= 0.0f) continue;
    std::array<int, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = block[a] * bsize;
      hi[a] = std::min(lo[a] + bsize - 1, n[a]);
    }
    LatticeWalker cells(o, dir, tb0, tb1, 1.0, lo, hi);
    std::array<int, 3> cell;
    double t0, t1;
    while (cells.next(cell, t0, t1)) {
      if (!(t1 > t0)) continue;
      // Reconstruction cell c = cell − 1 in index space; its corners, clamped.
      std::array<int, 3> c0, c1;
      std::array<double, 3> alpha, beta;  // local coordinate x(s) = alpha + beta s in [0, 1]
      for (int a = 0; a < 3; ++a) {
        const int c = cell[a] - 1;
        c0[a] = std::clamp(c, 0, n[a] - 1);
        c1[a] = std::clamp(c + 1, 0, n[a] - 1);
        alpha[a] = o[a] + t0 * dir[a] - cell[a];
        beta[a] = dir[a];
      }
      cell_corner_indices(g, c0, c1, corner_index);
      if (!any_extinction(g, ns, corner_index)) continue;
      corner_weight_cubics(alpha, beta, basis);
      auto combine = [&](const float* values) {
        Cubic r;
        for (int corner = 0; corner < 8; ++corner) {
          const double v = values[corner_index[corner]];
          for (int k = 0; k < 4; ++k) r.c[k] += v * basis[corner].c[k];
        }
        return r;
      };
      for (int s = 0; s < ns; ++s) {
        sig_a[s] = combine(g.sigma_a(s));
        sig_s[s] = combine(g.sigma_s(s));
      }
      component.temperature = combine(g.temperature());
      seg.t_begin = t0;
      seg.t_end = t1;
      seg.continuous_with_previous = t0 == previous_end;
      previous_end = t1;
      if (!visit(seg)) return;
    }
  }
}

void GridMedium::trace_majorants(const Ray& ray, double t_min, double t_max,
                                 const MajorantVisitor& visit) const {
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();
  Ray cell_ray;  // the same cell space as trace_segments
  if (!to_cell_space(g, ray, t_min, t_max, cell_ray)) return;
  const Vec3& o = cell_ray.origin;
  const Vec3& dir = cell_ray.direction;
  const auto& bd = majorants_.block_dims();
  LatticeWalker blocks(o, dir, t_min, t_max, majorants_.block_size(), {0, 0, 0},
                       {bd[0] - 1, bd[1] - 1, bd[2] - 1});
  std::vector<double> values(ns);
  std::array<int, 3> b;
  double t0, t1;
  while (blocks.next(b, t0, t1)) {
    if (!(t1 > t0) || majorants_.max_majorant(b[0], b[1], b[2]) <= 0.0f) continue;
    for (int s = 0; s < ns; ++s) values[s] = majorants_.majorant(b[0], b[1], b[2], s);
    if (!visit(MajorantSegment{t0, t1, values.data(), ns})) return;
  }
}

}  // namespace obscura
