#include "obscura/medium/composite_medium.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

CompositeMedium::CompositeMedium(std::vector<std::shared_ptr<const Medium>> children,
                                 const std::string& source) {
  for (auto& c : children)
    if (c) children_.push_back(std::move(c));
  if (children_.empty()) throw InputError(source, "clouds", "a composite medium needs a medium");
  wavelengths_um_ = children_.front()->wavelengths_um();
  for (std::size_t i = 0; i < children_.size(); ++i) {
    if (children_[i]->wavelengths_um() != wavelengths_um_)
      throw InputError(
          source, fmt::format("clouds/{}", i),
          fmt::format("spectral samples [{}] µm differ from the first cloud's [{}] µm; "
                      "overlapping clouds must share their wavelengths",
                      fmt::join(children_[i]->wavelengths_um(), ", "),
                      fmt::join(wavelengths_um_, ", ")));
    bounds_.expand(children_[i]->bounds());
  }
}

void CompositeMedium::coefficients_at(const Vec3& p, MediumPoint& out) const {
  const std::size_t n = wavelengths_um_.size();
  out.sigma_a.assign(n, 0.0);
  out.sigma_s.assign(n, 0.0);
  out.g.assign(n, 0.0);
  out.temperature_k = 0.0;
  MediumPoint child;
  double weight = 0.0, weighted_t = 0.0, plain_t = 0.0;
  for (const auto& c : children_) {
    c->coefficients_at(p, child);
    for (std::size_t k = 0; k < n; ++k) {
      out.sigma_a[k] += child.sigma_a[k];
      out.sigma_s[k] += child.sigma_s[k];
      out.g[k] += child.sigma_s[k] * child.g[k];
    }
    weight += child.sigma_a[0];
    weighted_t += child.sigma_a[0] * child.temperature_k;
    plain_t = std::max(plain_t, child.temperature_k);
  }
  for (std::size_t k = 0; k < n; ++k)
    out.g[k] = out.sigma_s[k] > 0 ? out.g[k] / out.sigma_s[k] : 0.0;
  out.temperature_k = weight > 0 ? weighted_t / weight : plain_t;
}

namespace {

// A child's segment copied out of its traversal (whose buffers are transient).
struct StoredSegment {
  double t0, t1;
  std::size_t cubics;  // offset of 2·spectral_count cubics (σa then σs) in the pool
  Cubic temperature;
};

}  // namespace

void CompositeMedium::trace_segments(const Ray& ray, double t_min, double t_max,
                                     const SegmentVisitor& visit) const {
  if (children_.size() == 1) {
    children_.front()->trace_segments(ray, t_min, t_max, visit);
    return;
  }
  const int ns = static_cast<int>(wavelengths_um_.size());
  std::vector<Cubic> pool;
  std::vector<std::vector<StoredSegment>> stored(children_.size());
  std::vector<double> breaks;
  for (std::size_t c = 0; c < children_.size(); ++c) {
    children_[c]->trace_segments(ray, t_min, t_max, [&](const MediumSegment& seg) {
      // A child reports one component per segment unless it is itself composite:
      // keep each component as its own stored segment.
      for (int k = 0; k < seg.component_count; ++k) {
        const std::size_t offset = pool.size();
        pool.insert(pool.end(), seg.components[k].sigma_a, seg.components[k].sigma_a + ns);
        pool.insert(pool.end(), seg.components[k].sigma_s, seg.components[k].sigma_s + ns);
        stored[c].push_back({seg.t_begin, seg.t_end, offset, seg.components[k].temperature});
      }
      breaks.push_back(seg.t_begin);
      breaks.push_back(seg.t_end);
      return true;
    });
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

  std::vector<std::size_t> cursor(children_.size(), 0);
  std::vector<Cubic> shifted;
  std::vector<MediumComponent> components;
  MediumSegment merged;
  merged.spectral_count = ns;
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    const double u0 = breaks[b], u1 = breaks[b + 1];
    shifted.clear();
    std::vector<std::pair<const StoredSegment*, double>> present;
    for (std::size_t c = 0; c < children_.size(); ++c) {
      auto& list = stored[c];
      std::size_t& i = cursor[c];
      while (i < list.size() && list[i].t1 <= u0) ++i;
      // Every stored segment of this child covering [u0, u1] (several only when
      // the child was itself composite).
      for (std::size_t j = i; j < list.size() && list[j].t0 <= u0; ++j)
        if (list[j].t1 >= u1) present.push_back({&list[j], u0 - list[j].t0});
    }
    if (present.empty()) continue;
    shifted.reserve(present.size() * 2 * ns);
    components.assign(present.size(), MediumComponent{});
    for (std::size_t p = 0; p < present.size(); ++p) {
      const auto& [s, d] = present[p];
      for (int k = 0; k < 2 * ns; ++k) shifted.push_back(pool[s->cubics + k].shifted(d));
      components[p].temperature = s->temperature.shifted(d);
    }
    // Pointers into `shifted` are taken only once it is complete (no reallocation after).
    for (std::size_t p = 0; p < present.size(); ++p) {
      components[p].sigma_a = shifted.data() + p * 2 * ns;
      components[p].sigma_s = shifted.data() + p * 2 * ns + ns;
    }
    merged.t_begin = u0;
    merged.t_end = u1;
    merged.components = components.data();
    merged.component_count = static_cast<int>(components.size());
    merged.continuous_with_previous = false;
    if (!visit(merged)) return;
  }
}

void CompositeMedium::trace_majorants(const Ray& ray, double t_min, double t_max,
                                      const MajorantVisitor& visit) const {
  if (children_.size() == 1) {
    children_.front()->trace_majorants(ray, t_min, t_max, visit);
    return;
  }
  const int ns = static_cast<int>(wavelengths_um_.size());
  struct Piece {
    double t0, t1;
    std::size_t values;  // offset in `pool`: the majorants, then the minorants
  };
  std::vector<double> pool, breaks;
  std::vector<std::vector<Piece>> pieces(children_.size());
  for (std::size_t c = 0; c < children_.size(); ++c)
    children_[c]->trace_majorants(ray, t_min, t_max, [&](const MajorantSegment& m) {
      pieces[c].push_back({m.t_begin, m.t_end, pool.size()});
      pool.insert(pool.end(), m.sigma_majorant, m.sigma_majorant + ns);
      if (m.sigma_minorant)
        pool.insert(pool.end(), m.sigma_minorant, m.sigma_minorant + ns);
      else
        pool.insert(pool.end(), static_cast<std::size_t>(ns), 0.0);
      breaks.push_back(m.t_begin);
      breaks.push_back(m.t_end);
      return true;
    });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<std::size_t> cursor(children_.size(), 0);
  std::vector<double> sum(ns), least(ns);
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    const double u0 = breaks[b], u1 = breaks[b + 1];
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(least.begin(), least.end(), 0.0);
    bool any = false;
    for (std::size_t c = 0; c < children_.size(); ++c) {
      std::size_t& i = cursor[c];
      while (i < pieces[c].size() && pieces[c][i].t1 <= u0) ++i;
      if (i < pieces[c].size() && pieces[c][i].t0 <= u0 && pieces[c][i].t1 >= u1) {
        const std::size_t v = pieces[c][i].values;
        for (int k = 0; k < ns; ++k) {
          sum[k] += pool[v + k];
          least[k] += pool[v + ns + k];
        }
        any = true;
      }
    }
    if (any && !visit(MajorantSegment{u0, u1, sum.data(), ns, least.data()})) return;
  }
}

void CompositeMedium::march_cells(const Ray& ray, double t_min, double t_max,
                                  const MarchOptions& options, MarchVisitor& visit) const {
  if (children_.size() == 1)
    children_.front()->march_cells(ray, t_min, t_max, options, visit);
  else
    Medium::march_cells(ray, t_min, t_max, options, visit);
}

std::optional<GridFrame> CompositeMedium::grid_frame() const {
  if (children_.size() == 1) return children_.front()->grid_frame();
  double voxel = 0.0;
  for (const auto& c : children_)
    if (const auto f = c->grid_frame())
      voxel = voxel > 0 ? std::min(voxel, f->placement.voxel_size_m) : f->placement.voxel_size_m;
  if (!(voxel > 0)) return std::nullopt;
  const BBox3 b = bounds();
  GridFrame frame;
  frame.trilinear = false;
  frame.placement.origin_m = b.lo;
  frame.placement.voxel_size_m = voxel;
  const Vec3 e = b.extent();
  frame.dims = {std::max(1, static_cast<int>(std::ceil(e.x / voxel))),
                std::max(1, static_cast<int>(std::ceil(e.y / voxel))),
                std::max(1, static_cast<int>(std::ceil(e.z / voxel)))};
  return frame;
}

bool CompositeMedium::may_be_nonzero(const BBox3& world_box) const {
  for (const auto& c : children_)
    if (c->may_be_nonzero(world_box)) return true;
  return false;
}

}  // namespace obscura
