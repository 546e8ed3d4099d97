#include "obscura/medium/keyframe_interpolation.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

bool same_layout(const VoxelGrid& a, const VoxelGrid& b) {
  const GridPlacement &p = a.placement(), &q = b.placement();
  return a.dims() == b.dims() && p.origin_m == q.origin_m && p.voxel_size_m == q.voxel_size_m &&
         p.rotation == q.rotation;
}

// Total extinction of voxel v over all spectral samples: zero means empty.
bool empty_voxel(const VoxelGrid& g, std::size_t v) {
  for (int s = 0; s < g.spectral_count(); ++s)
    if (g.sigma_a(s)[v] != 0.0f || g.sigma_s(s)[v] != 0.0f) return false;
  return true;
}

VoxelGrid interpolate_same_layout(const VoxelGrid& a, const VoxelGrid& b, double w) {
  VoxelGrid out(a.dims(), a.placement(), a.wavelengths_um());
  const double u = 1.0 - w;
  const std::size_t slice = static_cast<std::size_t>(a.dims().nx) * a.dims().ny;
  // Voxels are independent: z-slices in parallel, the same result for any thread count.
  parallel_for(static_cast<std::size_t>(a.dims().nz), 0, [&](std::size_t k) {
    const std::size_t begin = k * slice, end = begin + slice;
    for (int s = 0; s < a.spectral_count(); ++s) {
      const float *aa = a.sigma_a(s), *ba = b.sigma_a(s), *as = a.sigma_s(s), *bs = b.sigma_s(s);
      const float *ag = a.g(s), *bg = b.g(s);
      float *oa = out.sigma_a(s), *os = out.sigma_s(s), *og = out.g(s);
      for (std::size_t v = begin; v < end; ++v) {
        oa[v] = static_cast<float>(u * aa[v] + w * ba[v]);
        const double ws_a = u * as[v], ws_b = w * bs[v];
        const double sum = ws_a + ws_b;
        os[v] = static_cast<float>(sum);
        og[v] = static_cast<float>(sum > 0 ? (ws_a * ag[v] + ws_b * bg[v]) / sum
                                           : u * ag[v] + w * bg[v]);
      }
    }
    const float *at = a.temperature(), *bt = b.temperature();
    float* ot = out.temperature();
    for (std::size_t v = begin; v < end; ++v) {
      const bool ea = empty_voxel(a, v), eb = empty_voxel(b, v);
      if (ea && !eb)
        ot[v] = bt[v];
      else if (eb && !ea)
        ot[v] = at[v];
      else
        ot[v] = static_cast<float>(u * at[v] + w * bt[v]);
    }
  });
  return out;
}

}  // namespace

VoxelGrid resample_grid(const VoxelGrid& grid, GridDims dims, const GridPlacement& placement) {
  VoxelGrid out(dims, placement, grid.wavelengths_um());
  // A non-owning shared_ptr: the medium only reads `grid` during this call.
  const GridMedium medium(std::shared_ptr<const VoxelGrid>(&grid, [](const VoxelGrid*) {}));
  parallel_for(static_cast<std::size_t>(dims.nz), 0, [&](std::size_t kz) {
    const int k = static_cast<int>(kz);
    MediumPoint p;
    for (int j = 0; j < dims.ny; ++j)
      for (int i = 0; i < dims.nx; ++i) {
        medium.coefficients_at(placement.index_to_world(Vec3(i, j, k)), p);
        const std::size_t v = out.index(i, j, k);
        for (int s = 0; s < grid.spectral_count(); ++s) {
          out.sigma_a(s)[v] = static_cast<float>(p.sigma_a[s]);
          out.sigma_s(s)[v] = static_cast<float>(p.sigma_s[s]);
          out.g(s)[v] = static_cast<float>(p.g[s]);
        }
        out.temperature()[v] = static_cast<float>(p.temperature_k);
      }
  });
  return out;
}

VoxelGrid interpolate_keyframes(const VoxelGrid& a, const VoxelGrid& b, double weight,
                                const std::string& source) {
  if (!(weight >= 0.0 && weight <= 1.0))
    throw Error(fmt::format("interpolate_keyframes: weight {} outside [0, 1]", weight));
  if (a.wavelengths_um() != b.wavelengths_um())
    throw InputError(source, "keyframes",
                     "keyframes of one cloud must share their wavelengths (spectral samples)");
  if (weight == 0.0) return a;
  if (weight == 1.0) return b;
  if (same_layout(a, b)) return interpolate_same_layout(a, b, weight);
  if (!(a.placement().rotation == b.placement().rotation))
    throw InputError(source, "keyframes",
                     "keyframes of one cloud must share their grid rotation to be interpolated");
  // The union of both grids' boxes in their common rotated frame, at the finer voxel size.
  const Mat3& r = a.placement().rotation;
  const Mat3 rt = r.transposed();
  BBox3 local;
  for (const VoxelGrid* g : {&a, &b}) {
    const Vec3 lo = rt * g->placement().origin_m;
    const GridDims& d = g->dims();
    local.expand(lo);
    local.expand(lo + Vec3(d.nx, d.ny, d.nz) * g->placement().voxel_size_m);
  }
  GridPlacement p;
  p.rotation = r;
  p.voxel_size_m = std::min(a.placement().voxel_size_m, b.placement().voxel_size_m);
  p.origin_m = r * local.lo;
  const Vec3 extent = local.extent() / p.voxel_size_m;
  const GridDims dims{static_cast<int>(std::ceil(extent.x - 1e-9)),
                      static_cast<int>(std::ceil(extent.y - 1e-9)),
                      static_cast<int>(std::ceil(extent.z - 1e-9))};
  VoxelGrid::checked_storage_bytes(dims, a.spectral_count(), source);
  return interpolate_same_layout(resample_grid(a, dims, p), resample_grid(b, dims, p), weight);
}

}  // namespace obscura
