#include "obscura/prep/dispersion/dispersion_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "obscura/core/bbox.h"
#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/core/parallel.h"

namespace obscura {

namespace {

// Each puff deposits mass into the voxels within this many σ of its centre
// (or the coverage, if larger). Beyond 5σ a Gaussian holds 5.7·10⁻⁷ of its
// mass per axis, so the cut costs nothing measurable and bounds the work per
// puff (the cost of a frame is Σ over puffs of the voxels within reach).
constexpr double kMinFillSigmas = 5.0;

// A slab of z planes is the unit of parallel work; its accumulators (two
// doubles per voxel) are capped at this many voxels, 4 MiB, so that they stay
// in a core's cache while every puff of the frame is added: measured 25 % faster
// than 64 MiB slabs on large grids (docs/dispersion.md, "Benchmark").
constexpr std::size_t kMaxSlabVoxels = std::size_t{1} << 18;

void check_times(const std::vector<double>& times_s, const std::string& source) {
  if (times_s.empty()) throw InputError(source, "times_s", "expected at least one frame time");
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    if (!std::isfinite(times_s[i]))
      throw InputError(source, fmt::format("times_s/{}", i), "expected a finite time");
    if (i > 0 && !(times_s[i] > times_s[i - 1]))
      throw InputError(source, fmt::format("times_s/{}", i),
                       fmt::format("frame times must increase strictly ({} s after {} s)",
                                   times_s[i], times_s[i - 1]));
  }
}

void check_options(const DispersionGridOptions& o, const std::string& source) {
  if (!(std::isfinite(o.voxel_size_m) && o.voxel_size_m > 0))
    throw InputError(source, "voxel_size_m",
                     fmt::format("expected a voxel size > 0 m, found {}", o.voxel_size_m));
  if (!(o.coverage_sigmas >= 1 && o.coverage_sigmas <= 10))
    throw InputError(source, "coverage_sigmas",
                     fmt::format("expected a number in [1, 10], found {}", o.coverage_sigmas));
}

std::vector<std::vector<PuffState>> states_at(const DispersionModel& model,
                                              const std::vector<double>& times_s) {
  std::vector<std::vector<PuffState>> states;
  states.reserve(times_s.size());
  for (double t : times_s) states.push_back(model.puffs_at(t));
  return states;
}

DispersionGridLayout layout_of(const std::vector<std::vector<PuffState>>& states,
                               const DispersionGridOptions& o, const std::string& source) {
  BBox3 box;
  for (const auto& frame : states)
    for (const PuffState& s : frame) {
      const double rh = o.coverage_sigmas * s.sigma_horizontal_m;
      const double rz = o.coverage_sigmas * s.sigma_vertical_m;
      box.expand(Vec3(s.centre_m.x - rh, s.centre_m.y - rh, std::max(s.centre_m.z - rz, 0.0)));
      box.expand(Vec3(s.centre_m.x + rh, s.centre_m.y + rh, s.centre_m.z + rz));
    }
  if (box.empty())
    throw InputError(source, "times_s",
                     "no smoke device has released anything by the last requested time");
  const double h = o.voxel_size_m;
  // Snap outwards to whole voxels on a lattice anchored at the world origin,
  // so that the same cloud always gets the same voxel boundaries.
  const double i_lo = std::floor(box.lo.x / h), i_hi = std::ceil(box.hi.x / h);
  const double j_lo = std::floor(box.lo.y / h), j_hi = std::ceil(box.hi.y / h);
  const double k_hi = std::ceil(box.hi.z / h);
  const double counts[3] = {std::max(i_hi - i_lo, 1.0), std::max(j_hi - j_lo, 1.0),
                            std::max(k_hi, 1.0)};
  for (double n : counts)
    if (!(n < static_cast<double>(INT_MAX)))
      throw InputError(source, "voxel_size_m",
                       fmt::format("a {} m voxel gives {:.3g} voxels along one axis of the "
                                   "{:.4g} x {:.4g} x {:.4g} m cloud; use a larger voxel",
                                   h, n, box.extent().x, box.extent().y, box.hi.z));
  DispersionGridLayout layout;
  layout.dims = {static_cast<int>(counts[0]), static_cast<int>(counts[1]),
                 static_cast<int>(counts[2])};
  layout.placement.voxel_size_m = h;
  layout.placement.origin_m = {i_lo * h, j_lo * h, 0.0};
  return layout;
}

struct AxisRange {
  int lo = 0, hi = 0;  // voxels [lo, hi); empty if lo >= hi
};

// The voxels [e_i, e_i + h), e_i = origin + i h, within `reach_sigmas` σ of the
// centre along one axis, clipped to [clip_lo, clip_hi).
AxisRange reach(double centre, double sigma, double origin, double h, double reach_sigmas,
                int clip_lo, int clip_hi) {
  const double a = std::floor((centre - reach_sigmas * sigma - origin) / h);
  const double b = std::ceil((centre + reach_sigmas * sigma - origin) / h);
  const double lo = clip_lo, hi = clip_hi;
  return {static_cast<int>(std::clamp(a, lo, hi)), static_cast<int>(std::clamp(b, lo, hi))};
}

// Fraction of a unit Gaussian N(centre, σ²) in each voxel of the range along
// one axis (the exact integral, so a puff narrower than a voxel loses nothing):
// out[i − r.lo] += ½ [erf((e_{i+1} − c)/(√2 σ)) − erf((e_i − c)/(√2 σ))].
// Each edge's erf is a function of i alone, so a voxel's fraction does not
// depend on the range asked for: the slab decomposition cannot change a value.
void add_fractions(double centre, double sigma, double origin, double h, AxisRange r, double* out) {
  const double inv = 1.0 / (std::numbers::sqrt2 * sigma);
  double prev = std::erf((origin + r.lo * h - centre) * inv);
  for (int i = r.lo; i < r.hi; ++i) {
    const double next = std::erf((origin + (i + 1) * h - centre) * inv);
    out[i - r.lo] += std::max(0.5 * (next - prev), 0.0);
    prev = next;
  }
}

struct SlabWork {
  std::size_t frame;
  int k0, k1;  // z planes [k0, k1)
};

// Accumulates every puff of one frame into the planes [k0, k1) and writes the
// frame's concentration and temperature there.
void fill_slab(const std::vector<PuffState>& puffs, const DispersionGridLayout& layout,
               double reach_sigmas, double ambient_k, int k0, int k1, ConcentrationFrame& frame) {
  const GridDims& d = layout.dims;
  const double h = layout.placement.voxel_size_m;
  const Vec3 o = layout.placement.origin_m;
  const std::size_t plane = static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny);
  std::vector<double> c(plane * static_cast<std::size_t>(k1 - k0), 0.0);
  std::vector<double> e(c.size(), 0.0);  // Σ C_i ΔT_i
  std::vector<double> fx, fy, fz;
  const double inv_volume = 1.0 / (h * h * h);

  for (const PuffState& s : puffs) {
    const double sh = s.sigma_horizontal_m, sz = s.sigma_vertical_m;
    // The image puff at −H lies within the real puff's reach above the
    // ground whenever it reaches above it at all (−H + rσ <= H + rσ).
    const AxisRange rz = reach(s.centre_m.z, sz, o.z, h, reach_sigmas, k0, k1);
    if (rz.lo >= rz.hi) continue;
    const AxisRange rx = reach(s.centre_m.x, sh, o.x, h, reach_sigmas, 0, d.nx);
    const AxisRange ry = reach(s.centre_m.y, sh, o.y, h, reach_sigmas, 0, d.ny);
    if (rx.lo >= rx.hi || ry.lo >= ry.hi) continue;
    fx.assign(static_cast<std::size_t>(rx.hi - rx.lo), 0.0);
    fy.assign(static_cast<std::size_t>(ry.hi - ry.lo), 0.0);
    fz.assign(static_cast<std::size_t>(rz.hi - rz.lo), 0.0);
    add_fractions(s.centre_m.x, sh, o.x, h, rx, fx.data());
    add_fractions(s.centre_m.y, sh, o.y, h, ry, fy.data());
    add_fractions(s.centre_m.z, sz, o.z, h, rz, fz.data());
    add_fractions(-s.centre_m.z, sz, o.z, h, rz, fz.data());  // ground reflection

    const double w0 = s.mass_g * inv_volume;
    const double excess = s.temperature_excess_k;
    const int nx = rx.hi - rx.lo;
    for (int k = rz.lo; k < rz.hi; ++k) {
      const double wk = w0 * fz[static_cast<std::size_t>(k - rz.lo)];
      for (int j = ry.lo; j < ry.hi; ++j) {
        const double w = wk * fy[static_cast<std::size_t>(j - ry.lo)];
        const std::size_t row = static_cast<std::size_t>(k - k0) * plane +
                                static_cast<std::size_t>(j) * static_cast<std::size_t>(d.nx) +
                                static_cast<std::size_t>(rx.lo);
        double* cr = c.data() + row;
        for (int i = 0; i < nx; ++i) cr[i] += w * fx[static_cast<std::size_t>(i)];
        if (excess != 0.0) {
          const double we = w * excess;
          double* er = e.data() + row;
          for (int i = 0; i < nx; ++i) er[i] += we * fx[static_cast<std::size_t>(i)];
        }
      }
    }
  }

  const std::size_t base = static_cast<std::size_t>(k0) * plane;
  float* conc = frame.concentration_g_m3.values.data() + base;
  float* temp = frame.temperature_k->values.data() + base;
  for (std::size_t v = 0; v < c.size(); ++v) {
    conc[v] = static_cast<float>(c[v]);
    temp[v] = static_cast<float>(c[v] > 0 ? ambient_k + e[v] / c[v] : ambient_k);
  }
}

}  // namespace

DispersionGridLayout dispersion_grid_layout(const DispersionModel& model,
                                            const std::vector<double>& times_s,
                                            const DispersionGridOptions& options) {
  const std::string& source = model.config().source;
  check_times(times_s, source);
  check_options(options, source);
  return layout_of(states_at(model, times_s), options, source);
}

std::size_t dispersion_series_checked_bytes(const DispersionGridLayout& layout,
                                            std::size_t frame_count, const std::string& source,
                                            std::size_t scratch_bytes) {
  const GridDims& d = layout.dims;
  std::uint64_t bytes = 0;
  if (__builtin_mul_overflow(static_cast<std::uint64_t>(d.nx), static_cast<std::uint64_t>(d.ny),
                             &bytes) ||
      __builtin_mul_overflow(bytes, static_cast<std::uint64_t>(d.nz), &bytes) ||
      __builtin_mul_overflow(bytes, static_cast<std::uint64_t>(frame_count), &bytes) ||
      __builtin_mul_overflow(bytes, std::uint64_t{2 * sizeof(float)}, &bytes) ||
      __builtin_add_overflow(bytes, static_cast<std::uint64_t>(scratch_bytes), &bytes))
    throw InputError(source, "voxel_size_m",
                     fmt::format("{} frames of a {}x{}x{} grid overflow a 64-bit size; use a "
                                 "larger voxel or fewer frames",
                                 frame_count, d.nx, d.ny, d.nz));
  if (bytes > memory_limit_bytes())
    throw InputError(source, "voxel_size_m",
                     fmt::format("{} frames of a {}x{}x{} grid ({} m voxels, concentration and "
                                 "temperature) need {:.3g} GiB but only {}; use a larger voxel "
                                 "or fewer frames",
                                 frame_count, d.nx, d.ny, d.nz, layout.placement.voxel_size_m,
                                 bytes / 1073741824.0, memory_limit_text()));
  return static_cast<std::size_t>(bytes);
}

ConcentrationSeries dispersion_series(const DispersionModel& model,
                                      const std::vector<double>& times_s,
                                      const DispersionGridOptions& options) {
  const std::string& source = model.config().source;
  check_times(times_s, source);
  check_options(options, source);
  const auto states = states_at(model, times_s);
  const DispersionGridLayout layout = layout_of(states, options, source);

  // Work items are (frame, slab of z planes). Slabs are thin enough to keep
  // the accumulators small and, when there are fewer frames than threads, to
  // give every thread work; any split gives bit-identical values (every voxel
  // sums the same puffs in the same order with the same factors).
  const int threads = resolve_thread_count(options.threads);
  const GridDims& d = layout.dims;
  const std::size_t plane = static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny);
  const std::size_t frames = times_s.size();
  const std::size_t slabs_wanted = (4 * static_cast<std::size_t>(threads) + frames - 1) / frames;
  int depth = static_cast<int>((static_cast<std::size_t>(d.nz) + slabs_wanted - 1) / slabs_wanted);
  depth = std::min(depth, static_cast<int>(std::max<std::size_t>(kMaxSlabVoxels / plane, 1)));
  depth = std::max(depth, 1);
  // Two double accumulators per voxel of a slab, one slab per thread at a time.
  const double scratch = 2.0 * sizeof(double) * static_cast<double>(plane) * depth * threads;
  dispersion_series_checked_bytes(layout, frames, source,
                                  static_cast<std::size_t>(std::min(scratch, 1e18)));
  std::vector<SlabWork> work;
  for (std::size_t f = 0; f < frames; ++f)
    for (int k0 = 0; k0 < d.nz; k0 += depth) work.push_back({f, k0, std::min(k0 + depth, d.nz)});

  ConcentrationSeries series;
  series.source = source;
  series.frames.resize(times_s.size());
  for (std::size_t f = 0; f < times_s.size(); ++f) {
    ConcentrationFrame& frame = series.frames[f];
    frame.time_s = times_s[f];
    frame.concentration_g_m3.dims = layout.dims;
    frame.concentration_g_m3.placement = layout.placement;
    frame.concentration_g_m3.values.assign(layout.dims.count(), 0.0f);
    frame.temperature_k = frame.concentration_g_m3;
  }

  const double reach_sigmas = std::max(kMinFillSigmas, options.coverage_sigmas);
  const double ambient_k = model.config().ambient_temperature_k;
  parallel_for(work.size(), options.threads, [&](std::size_t w) {
    const SlabWork& item = work[w];
    fill_slab(states[item.frame], layout, reach_sigmas, ambient_k, item.k0, item.k1,
              series.frames[item.frame]);
  });
  return series;
}

ConcentrationSeries dispersion_series(const DispersionConfig& config,
                                      const std::vector<double>& times_s, double voxel_size_m,
                                      int threads) {
  DispersionGridOptions options;
  options.voxel_size_m = voxel_size_m;
  options.threads = threads;
  return dispersion_series(DispersionModel(config), times_s, options);
}

}  // namespace obscura
