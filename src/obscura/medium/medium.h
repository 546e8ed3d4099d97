#pragma once
// The small interface through which the render layer sees any participating
// medium (docs/architecture.md): a dense voxel grid, a homogeneous box, and later
// animated clouds and VDB-backed grids all plug in here unchanged.
#include <functional>
#include <optional>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/ray.h"
#include "obscura/medium/cubic.h"
#include "obscura/medium/medium_march.h"
#include "obscura/medium/spectral_lerp.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// Coefficients at one point, for the medium's own spectral samples.
struct MediumPoint {
  std::vector<double> sigma_a;  // 1/m
  std::vector<double> sigma_s;  // 1/m
  std::vector<double> g;        // HG asymmetry, dimensionless
  double temperature_k = 0.0;
};

// One medium's share of a segment: its coefficients and temperature as cubics
// in s = t − t_begin. Overlapping clouds give one component each: extinction
// adds, and each component emits σa B(T) at its own temperature.
struct MediumComponent {
  const Cubic* sigma_a = nullptr;  // spectral_count cubics, 1/m
  const Cubic* sigma_s = nullptr;  // spectral_count cubics, 1/m
  Cubic temperature;               // K
};

// A piece [t_begin, t_end] of a ray (t in metres along a unit direction) over
// which every property is a cubic polynomial in s = t − t_begin. Outside the
// segments a medium reports, its coefficients are zero.
struct MediumSegment {
  double t_begin = 0.0;
  double t_end = 0.0;
  int spectral_count = 0;
  const MediumComponent* components = nullptr;
  int component_count = 0;
  // True when the fields are continuous from the previous segment's end into
  // this one (neighbouring cells of one grid), so values there can be reused.
  bool continuous_with_previous = false;
};

// A piece [t_begin, t_end] of a ray over which σt ≤ sigma_majorant[k] for every
// spectral sample k (1/m): the bound that delta and ratio tracking sample
// against. Outside the pieces a medium reports, σt = 0. Where a medium knows
// one, sigma_minorant[k] ≤ σt over the piece too (the control of residual
// ratio tracking); null means 0.
struct MajorantSegment {
  double t_begin = 0.0;
  double t_end = 0.0;
  const double* sigma_majorant = nullptr;  // spectral_count values, 1/m
  int spectral_count = 0;
  const double* sigma_minorant = nullptr;  // spectral_count values, 1/m, or null
};

// A regular grid a medium is defined on (where it has one): what a cache of
// values over the medium aligns its own lattice with.
struct GridFrame {
  GridPlacement placement;
  GridDims dims;
  // The medium is exactly trilinear between the frame's voxel centres (a
  // grid's own frame), not just laid out over it.
  bool trilinear = true;
  // The voxels themselves when the medium is this one grid (clamped to the
  // edge values in the outer half voxel, zero beyond): what a lattice laid
  // on the frame may copy instead of sampling the medium point by point.
  const VoxelGrid* voxels = nullptr;
};

class Medium {
 public:
  // Return false to stop the traversal early.
  using SegmentVisitor = std::function<bool(const MediumSegment&)>;
  using MajorantVisitor = std::function<bool(const MajorantSegment&)>;

  virtual ~Medium() = default;

  // World-space box outside which the medium is empty.
  virtual BBox3 bounds() const = 0;
  // The spectral samples (µm, increasing) at which the medium is defined.
  virtual const std::vector<double>& wavelengths_um() const = 0;
  // Coefficients at a world point; zero coefficients (and 0 K) outside.
  virtual void coefficients_at(const Vec3& p, MediumPoint& out) const = 0;
  // σa, σs and g at a world point of spectral samples `first` and `second`
  // only (the two a SpectralLerp reads), and the temperature: the same values
  // coefficients_at gives them; out's other samples are left unspecified.
  // For what reads one wavelength: the inner loop of delta and ratio
  // tracking, the photons' emission lattice. The default evaluates every
  // sample; a grid overrides it.
  virtual void coefficients_of_samples(const Vec3& p, int first, int second,
                                       MediumPoint& out) const {
    (void)first;
    (void)second;
    coefficients_at(p, out);
  }
  // σt = σa + σs (1/m) at a world point at one wavelength between the
  // samples (lambda), the same bits as lambda(σa) + lambda(σs) of
  // coefficients_at: what a tentative collision of delta and ratio tracking
  // reads. The default evaluates the samples' whole point into `scratch`
  // (left unspecified); a grid overrides it with a lean lookup
  // (docs/performance.md).
  virtual double extinction_at(const Vec3& p, const SpectralLerp& lambda,
                               MediumPoint& scratch) const {
    coefficients_of_samples(p, lambda.sample0, lambda.sample1, scratch);
    return lambda(scratch.sigma_a.data()) + lambda(scratch.sigma_s.data());
  }
  // Visits, in order of increasing t, the segments of ray ∩ [t_min, t_max]
  // where the medium may be non-zero. `ray.direction` must be unit length.
  virtual void trace_segments(const Ray& ray, double t_min, double t_max,
                              const SegmentVisitor& visit) const = 0;
  // Visits, in order of increasing t, piecewise-constant upper bounds of σt
  // along the ray over [t_min, t_max] (coarse: one piece per majorant block).
  virtual void trace_majorants(const Ray& ray, double t_min, double t_max,
                               const MajorantVisitor& visit) const = 0;

  // Visits, in order of increasing t, the cells of ray ∩ [t_min, t_max] where
  // the medium may be non-zero with their coefficients at three points
  // (medium_march.h). The default evaluates trace_segments' cubics (g by
  // coefficients_at); a grid overrides it.
  virtual void march_cells(const Ray& ray, double t_min, double t_max, const MarchOptions& options,
                           MarchVisitor& visit) const;

  // The grid the medium's values live on, if it has one (the first cloud of
  // a composite); nothing otherwise.
  virtual std::optional<GridFrame> grid_frame() const { return std::nullopt; }
  // False only where the medium is certainly zero inside `world_box` (the
  // default: outside bounds()); a grid answers from its majorants.
  virtual bool may_be_nonzero(const BBox3& world_box) const;

  // Optical depth τ = ∫ σt ds along the ray over [t_min, t_max], one value per
  // spectral sample, integrated exactly from the segments' cubics.
  std::vector<double> optical_depth(const Ray& ray, double t_min, double t_max) const;
  // The same added into tau[0 … wavelengths_um().size()) (no allocation: for
  // callers that accumulate τ step by step along a ray). The default
  // integrates trace_segments' cubics; a grid overrides it.
  virtual void add_optical_depth(const Ray& ray, double t_min, double t_max, double* tau) const;
};

}  // namespace obscura
