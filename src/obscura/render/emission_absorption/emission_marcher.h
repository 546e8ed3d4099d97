#pragma once
// The fixed-order marcher: a MarchVisitor (medium/medium_march.h) that
// integrates, cell by cell, the emission of every spectral node of a band with
// the cell quadrature (cell_quadrature.h) and multiplies each node's
// transmittance by the cell's e^{−D}. The emissivity at a point is
// Σ_c σa,c B(T_c) over the overlapping clouds c; an in-scattering source adds
// σs J to it (the radiance cache's camera march), so emission and scattered
// light are integrated together with the exact transmittance of every cell.
// A point's values at a cell's exit are reused at the next cell's entry.
#include <array>

#include "obscura/medium/medium_march.h"
#include "obscura/render/emission_absorption/cell_quadrature.h"
#include "obscura/render/spectral_nodes.h"

namespace obscura {

// No in-scattering: emission–absorption.
struct NoInScattering {
  static constexpr bool kWantsG = false;
  // Adds σs J at point `p` of `cell` (at distance t along the ray) to
  // emissivity[j] for every node j, given σs and g per node.
  void add(const MarchCell&, int /*p*/, double /*t*/, const double* /*sigma_s*/,
           const double* /*g*/, double* /*emissivity*/) {}
};

template <typename InScattering>
class EmissionMarcher final : public MarchVisitor {
 public:
  // Adds to radiance[j] and multiplies transmittance[j], j over the nodes.
  EmissionMarcher(const SpectralNodes& nodes, InScattering& in_scattering, double* radiance,
                  double* transmittance)
      : nodes_(nodes),
        count_(static_cast<int>(nodes.size())),
        in_scattering_(in_scattering),
        radiance_(radiance),
        transmittance_(transmittance) {}

  std::uint64_t cells() const { return cells_; }

  bool visit(const MarchCell& cell) override {
    ++cells_;
    const double t[3] = {cell.t_begin, 0.5 * (cell.t_begin + cell.t_end), cell.t_end};
    const bool reuse = cell.continuous_with_previous && have_exit_;
    if (reuse)
      for (int j = 0; j < count_; ++j) {
        sigma_t_[0][j] = sigma_t_[2][j];
        emissivity_[0][j] = emissivity_[2][j];
      }
    for (int p = reuse ? 1 : 0; p < 3; ++p) point(cell, p, t[p]);
    have_exit_ = true;
    const double* sigma_t[3] = {sigma_t_[0].data(), sigma_t_[1].data(), sigma_t_[2].data()};
    const double* emissivity[3] = {emissivity_[0].data(), emissivity_[1].data(),
                                   emissivity_[2].data()};
    add_cell(cell.t_end - cell.t_begin, count_, sigma_t, emissivity, radiance_, transmittance_);
    return true;
  }

 private:
  using NodeArray = std::array<double, kMaxSpectralNodes>;

  // σt and the emissivity at point p for every node.
  void point(const MarchCell& cell, int p, double t) {
    NodeArray sigma_s, g;
    for (int j = 0; j < count_; ++j) {
      const SpectralNode& nd = nodes_.nodes()[j];
      const SpectralLerp lerp = nd.lerp();
      const PlanckTable& planck = *nd.planck_table;
      double sa = 0, ss = 0, gs = 0, em = 0;
      for (int c = 0; c < cell.component_count; ++c) {
        const MarchPoint& mp = cell.point[p][c];
        const double a = lerp(mp.sigma_a), b = lerp(mp.sigma_s);
        sa += a;
        ss += b;
        // g weighted by σs across wavelength as across space: the node's
        // σs g over its σs (as LatticeVolume's records).
        if constexpr (InScattering::kWantsG)
          gs += (1.0 - lerp.frac) * mp.sigma_s[lerp.sample0] * mp.g[lerp.sample0] +
                lerp.frac * mp.sigma_s[lerp.sample1] * mp.g[lerp.sample1];
        if (a != 0.0) em += a * planck(mp.temperature_k);
      }
      sigma_t_[p][j] = sa + ss;
      emissivity_[p][j] = em;
      sigma_s[j] = ss;
      g[j] = ss > 0.0 ? gs / ss : 0.0;
    }
    in_scattering_.add(cell, p, t, sigma_s.data(), g.data(), emissivity_[p].data());
  }

  const SpectralNodes& nodes_;
  int count_;
  InScattering& in_scattering_;
  double* radiance_;
  double* transmittance_;
  std::array<NodeArray, 3> sigma_t_{}, emissivity_{};
  bool have_exit_ = false;
  std::uint64_t cells_ = 0;
};

}  // namespace obscura
