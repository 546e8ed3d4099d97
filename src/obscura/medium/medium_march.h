#pragma once
// A medium seen cell by cell at three points: what the fixed-order marchers
// need (the emission–absorption cell quadrature and the radiance cache's
// camera march, render/emission_absorption/cell_quadrature.h). Where
// MediumSegment gives exact cubics (for exact integrals and adaptive
// quadrature), a MarchCell gives the coefficients at the entry (s = 0), the
// middle (s = h/2) and the exit (s = h) of each piece of the ray over which
// they are cubics: Simpson's rule on these three points integrates σt exactly,
// and a grid can evaluate them without building the cubics.
#include <cstddef>

namespace obscura {

// Overlapping clouds give one component each; a cell with more is refused.
inline constexpr int kMaxMarchComponents = 8;

// One component's coefficients at one point, per medium spectral sample.
struct MarchPoint {
  const double* sigma_a = nullptr;  // 1/m
  const double* sigma_s = nullptr;  // 1/m
  const double* g = nullptr;        // null unless the march was asked for g
  double temperature_k = 0.0;
};

struct MarchCell {
  double t_begin = 0.0, t_end = 0.0;  // m along the (unit) ray direction
  int spectral_count = 0;
  int component_count = 0;
  MarchPoint point[3][kMaxMarchComponents];  // [entry, middle, exit][component]
  // The entry values equal the previous cell's exit values (a neighbouring
  // cell of one grid): a marcher may reuse what it computed there.
  bool continuous_with_previous = false;
};

struct MarchOptions {
  bool with_g = false;  // also the asymmetry g at each point
  // Cells longer than this are cut into equal pieces no longer (a cache's
  // lattice spacing, say); the pieces stay within one cell of the medium.
  double max_cell_m = 1e300;
};

class MarchVisitor {
 public:
  // Return false to stop the march.
  virtual bool visit(const MarchCell& cell) = 0;

 protected:
  ~MarchVisitor() = default;
};

}  // namespace obscura
