#include "obscura/medium/grid_medium.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "obscura/core/host_device.h"
#include "obscura/medium/lattice_walker.h"

namespace obscura {

GridChannels::GridChannels(const VoxelGrid& grid) : temperature(grid.temperature()) {
  for (int s = 0; s < grid.spectral_count(); ++s) {
    sigma_a.push_back(grid.sigma_a(s));
    sigma_s.push_back(grid.sigma_s(s));
    g.push_back(grid.g(s));
  }
}

GridMedium::GridMedium(std::shared_ptr<const VoxelGrid> grid, int block_size)
    : grid_(std::move(grid)),
      majorants_(*grid_, block_size),
      bounds_(grid_->world_bounds()),
      channels_(*grid_) {}

namespace {

// Corner voxel indices and the fractional position inside the reconstruction
// cell that holds index coordinate u along one axis of n voxels; u must lie in
// [−½, n − ½] (so that the truncation below fits an int). floor by truncation
// and a correction, which equals std::floor there: x86-64 without SSE4.1 has
// no rounding instruction, and std::floor was 5 % of a photon tracing's
// instructions (docs/performance.md).
struct AxisLerp {
  int i0, i1;
  double f;
};
inline AxisLerp axis_lerp(double u, int n) {
  int ci = static_cast<int>(u);
  if (ci > u) --ci;
  return {std::clamp(ci, 0, n - 1), std::clamp(ci + 1, 0, n - 1), u - ci};
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

// Whether any corner has σa or σs ≠ 0 at any spectral sample (else the cell
// is clear).
bool any_extinction(const GridChannels& ch, const std::array<std::size_t, 8>& corner) {
  for (std::size_t s = 0; s < ch.sigma_a.size(); ++s)
    for (int c = 0; c < 8; ++c)
      if (ch.sigma_a[s][corner[c]] != 0.0f || ch.sigma_s[s][corner[c]] != 0.0f) return true;
  return false;
}

// Corner indices of the reconstruction cell `cell` (cell space), clamped at
// the grid's faces: x fastest, as VoxelGrid::index.
inline void corner_indices(const std::array<int, 3>& cell, const std::array<int, 3>& n,
                           std::array<std::size_t, 8>& corner) {
  const std::size_t x0 = static_cast<std::size_t>(std::clamp(cell[0] - 1, 0, n[0] - 1)),
                    x1 = static_cast<std::size_t>(std::clamp(cell[0], 0, n[0] - 1));
  const std::size_t y0 = static_cast<std::size_t>(std::clamp(cell[1] - 1, 0, n[1] - 1)),
                    y1 = static_cast<std::size_t>(std::clamp(cell[1], 0, n[1] - 1));
  const std::size_t z0 = static_cast<std::size_t>(std::clamp(cell[2] - 1, 0, n[2] - 1)),
                    z1 = static_cast<std::size_t>(std::clamp(cell[2], 0, n[2] - 1));
  const std::size_t nx = static_cast<std::size_t>(n[0]), nxy = nx * static_cast<std::size_t>(n[1]);
  const std::size_t r00 = y0 * nx + z0 * nxy, r10 = y1 * nx + z0 * nxy, r01 = y0 * nx + z1 * nxy,
                    r11 = y1 * nx + z1 * nxy;
  corner = {x0 + r00, x1 + r00, x0 + r10, x1 + r10, x0 + r01, x1 + r01, x0 + r11, x1 + r11};
}

// Calls visit(cell_ray, cell, corner, t0, t1) for the reconstruction cells
// along the world ray over [t_min, t_max], in order, that have a positive
// length and extinction at a corner (majorant blocks holding none are
// skipped whole); cell_ray is the ray in cell space (to_cell_space), t
// still in metres. Stops when visit returns false.
template <class Visit>
void for_each_cell(const VoxelGrid& g, const MajorantGrid& majorants, const GridChannels& channels,
                   const Ray& ray, double t_min, double t_max, Visit&& visit) {
  const GridDims& d = g.dims();
  const std::array<int, 3> n = {d.nx, d.ny, d.nz};
  Ray cell_ray;
  if (!to_cell_space(g, ray, t_min, t_max, cell_ray)) return;
  const Vec3& o = cell_ray.origin;
  const Vec3& dir = cell_ray.direction;
  const int bsize = majorants.block_size();
  const auto& bd = majorants.block_dims();
  LatticeWalker blocks(o, dir, t_min, t_max, bsize, {0, 0, 0}, {bd[0] - 1, bd[1] - 1, bd[2] - 1});
  std::array<int, 3> block, cell_index;
  std::array<std::size_t, 8> corner;
  double tb0, tb1, t0, t1;
  while (blocks.next(block, tb0, tb1)) {
    if (majorants.max_majorant(block[0], block[1], block[2]) <= 0.0f) continue;
    std::array<int, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = block[a] * bsize;
      hi[a] = std::min(lo[a] + bsize - 1, n[a]);
    }
    LatticeWalker cells(o, dir, tb0, tb1, 1.0, lo, hi);
    while (cells.next(cell_index, t0, t1)) {
      if (!(t1 > t0)) continue;
      corner_indices(cell_index, n, corner);
      if (!any_extinction(channels, corner)) continue;
      if (!visit(cell_ray, cell_index, corner, t0, t1)) return;
    }
  }
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

// The trilinear reconstruction's 8 voxels around index-space point u and
// their weights (corner c = x + 2y + 4z, each weight the product x·y·z of its
// axes' factors in that order); false outside the grid's box (plus the outer
// half voxels).
OBSCURA_ALWAYS_INLINE inline bool trilinear_corners(const VoxelGrid& g, const Vec3& u,
                                                    std::array<std::size_t, 8>& idx,
                                                    std::array<double, 8>& w) {
  const GridDims& d = g.dims();
  if (!(u.x >= -0.5 && u.x <= d.nx - 0.5 && u.y >= -0.5 && u.y <= d.ny - 0.5 && u.z >= -0.5 &&
        u.z <= d.nz - 0.5))
    return false;
  const AxisLerp ax = axis_lerp(u.x, d.nx), ay = axis_lerp(u.y, d.ny), az = axis_lerp(u.z, d.nz);
  // VoxelGrid::index as a base and one offset per axis.
  const std::size_t row = static_cast<std::size_t>(d.nx);
  const std::size_t plane = row * static_cast<std::size_t>(d.ny);
  const std::size_t base = g.index(ax.i0, ay.i0, az.i0);
  const std::size_t dx = static_cast<std::size_t>(ax.i1 - ax.i0);
  const std::size_t dy = row * static_cast<std::size_t>(ay.i1 - ay.i0);
  const std::size_t dz = plane * static_cast<std::size_t>(az.i1 - az.i0);
  const double wx[2] = {1 - ax.f, ax.f}, wy[2] = {1 - ay.f, ay.f};
  const double xy[4] = {wx[0] * wy[0], wx[1] * wy[0], wx[0] * wy[1], wx[1] * wy[1]};
  const std::size_t oxy[4] = {0, dx, dy, dx + dy};
  for (int c = 0; c < 4; ++c) {
    idx[c] = base + oxy[c];
    idx[c + 4] = base + oxy[c] + dz;
    w[c] = xy[c] * (1 - az.f);
    w[c + 4] = xy[c] * az.f;
  }
  return true;
}

// The trilinear sums of σa, σs and, with kWithG, g (weighted by
// scattering, so that mixing clear and scattering voxels keeps the
// scatterers' phase function) of spectral sample s at the corners `idx`
// with weights `w`: every point evaluation of the grid (coefficients_at, the
// march's points, the optical depth) sums them this way, so they agree to
// the bit.
struct SampleSums {
  double sigma_a, sigma_s, g;
};
template <bool kWithG>
inline SampleSums sample_sums(const GridChannels& ch, int s, const std::array<std::size_t, 8>& idx,
                              const std::array<double, 8>& w) {
  const float* sigma_a = ch.sigma_a[static_cast<std::size_t>(s)];
  const float* sigma_s = ch.sigma_s[static_cast<std::size_t>(s)];
  const float* g = ch.g[static_cast<std::size_t>(s)];
  double sa = 0, ss = 0, gs = 0;
  for (int c = 0; c < 8; ++c) {
    sa += w[c] * sigma_a[idx[c]];
    const double ssc = w[c] * sigma_s[idx[c]];
    ss += ssc;
    if constexpr (kWithG) gs += ssc * g[idx[c]];
  }
  return {sa, ss, kWithG && ss > 0 ? gs / ss : 0.0};
}

// Sample s's sums (σa, σs, g) into `out`.
void sample_coefficients(const GridChannels& ch, int s, const std::array<std::size_t, 8>& idx,
                         const std::array<double, 8>& w, MediumPoint& out) {
  const SampleSums sums = sample_sums<true>(ch, s, idx, w);
  out.sigma_a[s] = sums.sigma_a;
  out.sigma_s[s] = sums.sigma_s;
  out.g[s] = sums.g;
}

double trilinear_temperature(const GridChannels& ch, const std::array<std::size_t, 8>& idx,
                             const std::array<double, 8>& w) {
  double t = 0;
  for (int c = 0; c < 8; ++c) t += w[c] * ch.temperature[idx[c]];
  return t;
}

// Spectral samples `first` and `second` at world point p into `out` (σa,
// σs, g) and the temperature, the same bits as coefficients_at.
void samples_at(const VoxelGrid& g, const GridChannels& ch, const Vec3& p, int first, int second,
                MediumPoint& out) {
  const std::size_t ns = static_cast<std::size_t>(g.spectral_count());
  if (out.sigma_a.size() != ns || out.sigma_s.size() != ns || out.g.size() != ns) {
    out.sigma_a.resize(ns);
    out.sigma_s.resize(ns);
    out.g.resize(ns);
  }
  const std::size_t s0 = static_cast<std::size_t>(first), s1 = static_cast<std::size_t>(second);
  std::array<std::size_t, 8> idx;
  std::array<double, 8> w;
  if (!trilinear_corners(g, g.placement().world_to_index(p), idx, w)) {
    for (const std::size_t s : {s0, s1}) {
      out.sigma_a[s] = 0.0;
      out.sigma_s[s] = 0.0;
      out.g[s] = 0.0;
    }
    out.temperature_k = 0.0;
    return;
  }
  sample_coefficients(ch, first, idx, w, out);
  if (second != first) sample_coefficients(ch, second, idx, w, out);
  out.temperature_k = trilinear_temperature(ch, idx, w);
}

}  // namespace

void GridMedium::coefficients_at(const Vec3& p, MediumPoint& out) const {
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();
  out.sigma_a.assign(ns, 0.0);
  out.sigma_s.assign(ns, 0.0);
  out.g.assign(ns, 0.0);
  out.temperature_k = 0.0;
  std::array<std::size_t, 8> idx;
  std::array<double, 8> w;
  if (!trilinear_corners(g, g.placement().world_to_index(p), idx, w)) return;
  for (int s = 0; s < ns; ++s) sample_coefficients(channels_, s, idx, w, out);
  out.temperature_k = trilinear_temperature(channels_, idx, w);
}

// Two of the samples only: a tracking step or an emission lattice at one
// wavelength reads no more, and a tracking step only their σa and σs
// (docs/performance.md).
void GridMedium::coefficients_of_samples(const Vec3& p, int first, int second,
                                         MediumPoint& out) const {
  samples_at(*grid_, channels_, p, first, second, out);
}

// The lerp's two samples' σa and σs (sample_sums, so the same bits),
// without a MediumPoint: a tentative collision is most of a photon's
// lookups (docs/performance.md).
double GridMedium::extinction_at(const Vec3& p, const SpectralLerp& lambda, MediumPoint&) const {
  std::array<std::size_t, 8> idx;
  std::array<double, 8> w;
  if (!trilinear_corners(*grid_, grid_->placement().world_to_index(p), idx, w)) return 0.0;
  const SampleSums a = sample_sums<false>(channels_, lambda.sample0, idx, w);
  const SampleSums b = sample_sums<false>(channels_, lambda.sample1, idx, w);
  const double f = lambda.frac;
  return ((1.0 - f) * a.sigma_a + f * b.sigma_a) + ((1.0 - f) * a.sigma_s + f * b.sigma_s);
}

void GridMedium::trace_segments(const Ray& ray, double t_min, double t_max,
                                const SegmentVisitor& visit) const {
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();

  // Allocated at the first cell: a ray that misses the grid costs nothing.
  std::vector<Cubic> cubics;
  MediumComponent component;
  MediumSegment seg;
  seg.spectral_count = ns;
  seg.components = &component;
  seg.component_count = 1;
  double previous_end = -1.0;

  std::array<Cubic, 8> basis;
  for_each_cell(g, majorants_, channels_, ray, t_min, t_max,
                [&](const Ray& cell_ray, const std::array<int, 3>& cell,
                    const std::array<std::size_t, 8>& corner_index, double t0, double t1) {
                  const Vec3 &o = cell_ray.origin, &dir = cell_ray.direction;
                  // Local coordinate x(s) = alpha + beta s in [0, 1] across the
                  // reconstruction cell c = cell − 1 (index space).
                  std::array<double, 3> alpha, beta;
                  for (int a = 0; a < 3; ++a) {
                    alpha[a] = o[a] + t0 * dir[a] - cell[a];
                    beta[a] = dir[a];
                  }
                  corner_weight_cubics(alpha, beta, basis);
                  if (cubics.empty()) {
                    cubics.resize(2 * static_cast<std::size_t>(ns));
                    component.sigma_a = cubics.data();
                    component.sigma_s = cubics.data() + ns;
                  }
                  auto combine = [&](const float* values) {
                    Cubic r;
                    for (int corner = 0; corner < 8; ++corner) {
                      const double v = values[corner_index[corner]];
                      for (int k = 0; k < 4; ++k) r.c[k] += v * basis[corner].c[k];
                    }
                    return r;
                  };
                  for (int s = 0; s < ns; ++s) {
                    cubics[static_cast<std::size_t>(s)] = combine(channels_.sigma_a[s]);
                    cubics[static_cast<std::size_t>(ns + s)] = combine(channels_.sigma_s[s]);
                  }
                  component.temperature = combine(channels_.temperature);
                  seg.t_begin = t0;
                  seg.t_end = t1;
                  seg.continuous_with_previous = t0 == previous_end;
                  previous_end = t1;
                  return visit(seg);
                });
}

namespace {

// The trilinear weights of the 8 corners at local coordinates f in [0, 1]³.
inline void corner_weights(const std::array<double, 3>& f, std::array<double, 8>& w) {
  const double x0 = 1 - f[0], y0 = 1 - f[1], z0 = 1 - f[2];
  w[0] = x0 * y0 * z0;
  w[1] = f[0] * y0 * z0;
  w[2] = x0 * f[1] * z0;
  w[3] = f[0] * f[1] * z0;
  w[4] = x0 * y0 * f[2];
  w[5] = f[0] * y0 * f[2];
  w[6] = x0 * f[1] * f[2];
  w[7] = f[0] * f[1] * f[2];
}

// The coefficients at one point of a cell into `out` (σa, σs, then g when
// asked, per sample) and its temperature: the same trilinear field as
// coefficients_at, g weighted by scattering.
double evaluate_point(const GridChannels& ch, int ns, const std::array<std::size_t, 8>& corner,
                      const std::array<double, 8>& w, bool with_g, double* out) {
  for (int s = 0; s < ns; ++s) {
    const SampleSums sums =
        with_g ? sample_sums<true>(ch, s, corner, w) : sample_sums<false>(ch, s, corner, w);
    out[s] = sums.sigma_a;
    out[ns + s] = sums.sigma_s;
    if (with_g) out[2 * ns + s] = sums.g;
  }
  return trilinear_temperature(ch, corner, w);
}

// The trilinear weights at point o + t dir of the cell-space ray in
// reconstruction cell `cell`, its fractions clamped against rounding.
inline void weights_at(const Ray& cell_ray, double t, const std::array<int, 3>& cell,
                       std::array<double, 8>& w) {
  std::array<double, 3> f;
  for (int a = 0; a < 3; ++a)
    f[a] = std::clamp(cell_ray.origin[a] + t * cell_ray.direction[a] - cell[a], 0.0, 1.0);
  corner_weights(f, w);
}

// σa + σs per sample at one point of a cell into `out`: the optical depth's
// Simpson rule adds the march's point sums so (and so has their bits).
void extinction_at_point(const GridChannels& ch, int ns, const std::array<std::size_t, 8>& corner,
                         const std::array<double, 8>& w, double* out) {
  for (int s = 0; s < ns; ++s) {
    const SampleSums sums = sample_sums<false>(ch, s, corner, w);
    out[s] = sums.sigma_a + sums.sigma_s;
  }
}

}  // namespace

void GridMedium::march_cells(const Ray& ray, double t_min, double t_max,
                             const MarchOptions& options, MarchVisitor& visit) const {
  const bool with_g = options.with_g;
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();
  // Three point buffers (entry, middle, exit), swapped rather than copied
  // when a cell's entry is the previous cell's exit. Per thread: no
  // allocation per ray once warm.
  const std::size_t per_point = static_cast<std::size_t>(with_g ? 3 : 2) * ns;
  thread_local std::vector<double> buffer;
  buffer.resize(3 * per_point);
  double* slot[3] = {buffer.data(), buffer.data() + per_point, buffer.data() + 2 * per_point};
  double temperature[3] = {0, 0, 0};
  MarchCell cell;
  cell.spectral_count = ns;
  cell.component_count = 1;
  double previous_end = -1.0;

  std::array<double, 8> w;
  for_each_cell(g, majorants_, channels_, ray, t_min, t_max,
                [&](const Ray& cell_ray, const std::array<int, 3>& cell_index,
                    const std::array<std::size_t, 8>& corner, double t0, double t1) {
                  // Usually one piece: the cell itself.
                  const int pieces =
                      std::max(1, static_cast<int>(std::ceil((t1 - t0) / options.max_cell_m)));
                  const double hp = (t1 - t0) / pieces;
                  for (int q = 0; q < pieces; ++q) {
                    // The exit as the next entry's own expression, so that
                    // the two are the same double (Medium::march_cells).
                    const double p0 = t0 + q * hp, p1 = q + 1 == pieces ? t1 : t0 + (q + 1) * hp;
                    const bool continuous = p0 == previous_end;
                    if (continuous) {
                      std::swap(slot[0], slot[2]);
                      temperature[0] = temperature[2];
                    }
                    const double ts[3] = {p0, 0.5 * (p0 + p1), p1};
                    for (int p = continuous ? 1 : 0; p < 3; ++p) {
                      weights_at(cell_ray, ts[p], cell_index, w);
                      temperature[p] = evaluate_point(channels_, ns, corner, w, with_g, slot[p]);
                    }
                    for (int p = 0; p < 3; ++p)
                      cell.point[p][0] = {slot[p], slot[p] + ns,
                                          with_g ? slot[p] + 2 * ns : nullptr, temperature[p]};
                    cell.t_begin = p0;
                    cell.t_end = p1;
                    cell.continuous_with_previous = continuous;
                    previous_end = p1;
                    if (!visit.visit(cell)) return false;
                  }
                  return true;
                });
}

void GridMedium::add_optical_depth(const Ray& ray, double t_min, double t_max, double* tau) const {
  // march_cells' cells and points, σt alone per point (no temperature, no
  // visitor): the sun's depth at every node of a radiance cache's lattice
  // is a ray each, most of a small frame's fixed cost (docs/performance.md).
  const VoxelGrid& g = *grid_;
  const int ns = g.spectral_count();
  // σt per sample at the cell's entry, middle and exit, the entry reused
  // from the previous exit. Per thread: no allocation per ray once warm.
  thread_local std::vector<double> buffer;
  buffer.resize(3 * static_cast<std::size_t>(ns));
  double* at[3] = {buffer.data(), buffer.data() + ns, buffer.data() + 2 * ns};
  double previous_end = -1.0;
  std::array<double, 8> w;
  for_each_cell(g, majorants_, channels_, ray, t_min, t_max,
                [&](const Ray& cell_ray, const std::array<int, 3>& cell_index,
                    const std::array<std::size_t, 8>& corner, double t0, double t1) {
                  const bool continuous = t0 == previous_end;
                  if (continuous) std::swap(at[0], at[2]);
                  const double ts[3] = {t0, 0.5 * (t0 + t1), t1};
                  for (int p = continuous ? 1 : 0; p < 3; ++p) {
                    weights_at(cell_ray, ts[p], cell_index, w);
                    extinction_at_point(channels_, ns, corner, w, at[p]);
                  }
                  // Simpson's rule, exact for the trilinear σt (a cubic).
                  const double h = t1 - t0;
                  for (int k = 0; k < ns; ++k)
                    tau[k] += h / 6.0 * (at[0][k] + 4.0 * at[1][k] + at[2][k]);
                  previous_end = t1;
                  return true;
                });
}

bool GridMedium::may_be_nonzero(const BBox3& world_box) const {
  if (!Medium::may_be_nonzero(world_box)) return false;
  // The box's corners in cell space (w = index + 1), a conservative range of cells.
  const VoxelGrid& g = *grid_;
  BBox3 cells;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? world_box.hi.x : world_box.lo.x,
                 (corner & 2) ? world_box.hi.y : world_box.lo.y,
                 (corner & 4) ? world_box.hi.z : world_box.lo.z);
    cells.expand(g.placement().world_to_index(p) + Vec3(1, 1, 1));
  }
  const std::array<int, 3> n = {g.dims().nx, g.dims().ny, g.dims().nz};
  const int bsize = majorants_.block_size();
  const auto& bd = majorants_.block_dims();
  std::array<int, 3> b0, b1;
  for (int a = 0; a < 3; ++a) {
    const int c0 = std::clamp(static_cast<int>(std::floor(cells.lo[a])), 0, n[a]);
    const int c1 = std::clamp(static_cast<int>(std::floor(cells.hi[a])), 0, n[a]);
    b0[a] = std::min(c0 / bsize, bd[a] - 1);
    b1[a] = std::min(c1 / bsize, bd[a] - 1);
  }
  for (int z = b0[2]; z <= b1[2]; ++z)
    for (int y = b0[1]; y <= b1[1]; ++y)
      for (int x = b0[0]; x <= b1[0]; ++x)
        if (majorants_.max_majorant(x, y, z) > 0.0f) return true;
  return false;
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
  // The pieces' values on the stack for up to kOnStack wavelengths (a
  // photon's every flight walks here), on the heap beyond.
  constexpr int kOnStack = 16;
  std::array<double, 2 * kOnStack> on_stack;
  std::vector<double> on_heap(ns > kOnStack ? 2 * static_cast<std::size_t>(ns) : 0);
  double* const values = ns > kOnStack ? on_heap.data() : on_stack.data();
  double* const least = values + ns;
  std::array<int, 3> b;
  double t0, t1;
  while (blocks.next(b, t0, t1)) {
    if (!(t1 > t0) || majorants_.max_majorant(b[0], b[1], b[2]) <= 0.0f) continue;
    for (int s = 0; s < ns; ++s) {
      values[s] = majorants_.majorant(b[0], b[1], b[2], s);
      least[s] = majorants_.minorant(b[0], b[1], b[2], s);
    }
    if (!visit(MajorantSegment{t0, t1, values, ns, least})) return;
  }
}

}  // namespace obscura
