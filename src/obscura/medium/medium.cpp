#include "obscura/medium/medium.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "obscura/core/error.h"

namespace obscura {

void Medium::add_optical_depth(const Ray& ray, double t_min, double t_max, double* tau) const {
  trace_segments(ray, t_min, t_max, [&](const MediumSegment& seg) {
    const double h = seg.t_end - seg.t_begin;
    for (int c = 0; c < seg.component_count; ++c)
      for (int k = 0; k < seg.spectral_count; ++k)
        tau[k] +=
            seg.components[c].sigma_a[k].integral(h) + seg.components[c].sigma_s[k].integral(h);
    return true;
  });
}

std::vector<double> Medium::optical_depth(const Ray& ray, double t_min, double t_max) const {
  std::vector<double> tau(wavelengths_um().size(), 0.0);
  add_optical_depth(ray, t_min, t_max, tau.data());
  return tau;
}

}  // namespace obscura

namespace obscura {

bool Medium::may_be_nonzero(const BBox3& world_box) const {
  const BBox3 b = bounds();
  for (int a = 0; a < 3; ++a)
    if (world_box.hi[a] < b.lo[a] || world_box.lo[a] > b.hi[a]) return false;
  return true;
}

void Medium::march_cells(const Ray& ray, double t_min, double t_max, const MarchOptions& options,
                         MarchVisitor& visit) const {
  // Scratch per thread: [point][component][σa | σs | g][sample].
  thread_local std::vector<double> values;
  thread_local MediumPoint at;
  const int ns = static_cast<int>(wavelengths_um().size());
  const bool with_g = options.with_g;
  MarchCell cell;
  cell.spectral_count = ns;
  trace_segments(ray, t_min, t_max, [&](const MediumSegment& seg) {
    if (seg.component_count > kMaxMarchComponents)
      throw Error("medium: more than " + std::to_string(kMaxMarchComponents) +
                  " overlapping clouds in one cell");
    const double h = seg.t_end - seg.t_begin;
    const int pieces = std::max(1, static_cast<int>(std::ceil(h / options.max_cell_m)));
    const double hp = h / pieces;
    const std::size_t per_component = 3 * static_cast<std::size_t>(ns);
    values.resize(3 * per_component * static_cast<std::size_t>(seg.component_count));
    for (int q = 0; q < pieces; ++q) {
      // A piece's exit as (q + 1) hp, the next entry's own expression, so
      // that the two are the same double (a marcher finds what it read there
      // by its distance: an exit of q hp + hp missed it one time in three).
      const double s0 = q * hp;
      const double s_at[3] = {s0, s0 + 0.5 * hp, q + 1 == pieces ? h : (q + 1) * hp};
      for (int p = 0; p < 3; ++p) {
        if (p == 0 && q > 0) {
          // A piece's entry is the last piece's exit: its values are copied,
          // not evaluated again (a third of the evaluations on a long cell).
          const std::size_t block = per_component * static_cast<std::size_t>(seg.component_count);
          std::copy_n(values.data() + 2 * block, block, values.data());
          for (int c = 0; c < seg.component_count; ++c) {
            double* v = values.data() + static_cast<std::size_t>(c) * per_component;
            cell.point[0][c] = {v, v + ns, with_g ? v + 2 * ns : nullptr,
                                cell.point[2][c].temperature_k};
          }
          continue;
        }
        if (with_g) coefficients_at(ray.at(seg.t_begin + s_at[p]), at);
        for (int c = 0; c < seg.component_count; ++c) {
          double* v = values.data() +
                      (static_cast<std::size_t>(p) * seg.component_count + c) * per_component;
          const MediumComponent& comp = seg.components[c];
          for (int k = 0; k < ns; ++k) {
            v[k] = comp.sigma_a[k](s_at[p]);
            v[ns + k] = comp.sigma_s[k](s_at[p]);
            // A composite's g is the σs-weighted mean over its components: each
            // component gets it, and the marcher's own σs weighting returns it.
            v[2 * ns + k] = with_g ? at.g[k] : 0.0;
          }
          cell.point[p][c] = {v, v + ns, with_g ? v + 2 * ns : nullptr, comp.temperature(s_at[p])};
        }
      }
      cell.t_begin = seg.t_begin + s_at[0];
      cell.t_end = seg.t_begin + s_at[2];
      cell.component_count = seg.component_count;
      cell.continuous_with_previous = q > 0 || seg.continuous_with_previous;
      if (!visit.visit(cell)) return false;
    }
    return true;
  });
}

}  // namespace obscura
