#pragma once
// The fixed-order marcher: a MarchVisitor (medium/medium_march.h) that
// integrates, cell by cell, the emission of every spectral node of a band with
// the cell quadrature (cell_quadrature.h) and multiplies each node's
// transmittance by the cell's e^{−D}. The emissivity at a point is
// Σ_c σa,c B(T_c) over the overlapping clouds c; an in-scattering source adds
// σs J to it (the radiance cache's camera march), so emission and scattered
// light are integrated together with the exact transmittance of every cell.
// A point's values at a cell's exit are reused at the next cell's entry.
//
// An in-scattering source that lights the medium by a sun may tell the
// sun's optical depth along the ray (sun_depths(t, tau): τ_sun per node at
// distance t), the medium at a point (medium_at(t, point)) and the sun's part
// of what it adds (add with a seventh argument, sun[j] = σs J_sun; add_sun,
// that part alone): where τ_sun climbs by more than 1 across a
// cell, that node's sun part is integrated over equal pieces of the cell
// (cell_pieces, cell_quadrature.h), the medium and the sun's light read at
// the pieces' points, and the rest of the emissivity over the whole cell, as
// the lattice march does (render/lattice/lattice_view_march.h,
// docs/physics.md).
//
// An in-scattering source that keeps part of the scattering in the ray's own
// direction (forward_fraction(g): delta-M's f, the radiance cache's rays
// without a forward peak) has the radiance integrated with σt − f σs and
// seen through `attenuation`, the transmittance staying exact
// (add_cell_forward, cell_quadrature.h).
#include <array>
#include <vector>

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
  // Adds to radiance[j] and multiplies transmittance[j] (and, for a source
  // that keeps forward scattering, attenuation[j]), j over the nodes.
  EmissionMarcher(const SpectralNodes& nodes, InScattering& in_scattering, double* radiance,
                  double* transmittance, double* attenuation = nullptr)
      : nodes_(nodes),
        count_(static_cast<int>(nodes.size())),
        in_scattering_(in_scattering),
        radiance_(radiance),
        transmittance_(transmittance),
        attenuation_(attenuation) {}

  std::uint64_t cells() const { return cells_; }

  bool visit(const MarchCell& cell) override {
    ++cells_;
    const double t[3] = {cell.t_begin, 0.5 * (cell.t_begin + cell.t_end), cell.t_end};
    const bool reuse = cell.continuous_with_previous && have_exit_;
    if (reuse)
      for (int j = 0; j < count_; ++j) {
        sigma_t_[0][j] = sigma_t_[2][j];
        emissivity_[0][j] = emissivity_[2][j];
        forward_[0][j] = forward_[2][j];
        if constexpr (kCutsSteepCells) sun_[0][j] = sun_[2][j];
      }
    for (int p = reuse ? 1 : 0; p < 3; ++p) point(cell, p, t[p]);
    have_exit_ = true;
    const double* sigma_t[3] = {sigma_t_[0].data(), sigma_t_[1].data(), sigma_t_[2].data()};
    const double* forward[3] = {forward_[0].data(), forward_[1].data(), forward_[2].data()};
    const double* emissivity[3] = {emissivity_[0].data(), emissivity_[1].data(),
                                   emissivity_[2].data()};
    if constexpr (kCutsSteepCells) {
      NodeArray tau0, tau1;
      in_scattering_.sun_depths(t[0], tau0.data());
      in_scattering_.sun_depths(t[2], tau1.data());
      bool any_cut = false;
      for (int j = 0; j < count_; ++j) any_cut = any_cut || cell_pieces(tau1[j] - tau0[j]) > 1;
      if (any_cut) {
        for (int j = 0; j < count_; ++j) {
          const int pieces = cell_pieces(tau1[j] - tau0[j]);
          if (pieces > 1) {
            cut_cell(cell, j, pieces);
            continue;
          }
          const double* st[3] = {sigma_t[0] + j, sigma_t[1] + j, sigma_t[2] + j};
          const double* fw[3] = {forward[0] + j, forward[1] + j, forward[2] + j};
          const double* em[3] = {emissivity[0] + j, emissivity[1] + j, emissivity[2] + j};
          add(cell.t_end - cell.t_begin, 1, st, fw, em, j);
        }
        return true;
      }
    }
    add(cell.t_end - cell.t_begin, count_, sigma_t, forward, emissivity, 0);
    return true;
  }

 private:
  using NodeArray = std::array<double, kMaxSpectralNodes>;
  static constexpr bool kCutsSteepCells =
      requires(InScattering & in, double* tau, MediumPoint& m, const MarchCell& cell) {
    in.sun_depths(0.0, tau);
    in.medium_at(0.0, m);
    in.add_sun(cell, 0, 0.0, tau, tau, tau);
  };
  static constexpr bool kKeepsForward = requires(InScattering & in) { in.forward_fraction(0.0); };

  // Nodes j0 … j0 + count − 1 of a cell of length h.
  void add(double h, int count, const double* const st[3], const double* const fw[3],
           const double* const em[3], int j0) {
    if constexpr (kKeepsForward)
      add_cell_forward(h, count, st, fw, em, radiance_ + j0, transmittance_ + j0,
                       attenuation_ + j0);
    else
      add_cell(h, count, st, em, radiance_ + j0, transmittance_ + j0);
  }

  // Delta-M's f σs at a point (0 without it).
  double forward_at(double sigma_s, double g) const {
    if constexpr (kKeepsForward)
      return sigma_s > 0.0 ? in_scattering_.forward_fraction(g) * sigma_s : 0.0;
    else
      return 0.0;
  }

  // Node j's cell with the sun's part in `pieces` equal pieces: the medium
  // (InScattering::medium_at: σa, σs and g at a point) and the sun's light
  // read at each piece's middle and exit (the last exit is the cell's); the
  // rest over the whole cell.
  void cut_cell(const MarchCell& cell, int j, int pieces) {
    const double t0 = cell.t_begin, step = (cell.t_end - cell.t_begin) / pieces;
    const SpectralLerp lerp = nodes_.nodes()[j].lerp();
    NodeArray sigma_s{}, g{}, emissivity{};
    double st[3], fw[3], em[3];
    st[2] = sigma_t_[0][j];
    fw[2] = forward_[0][j];
    em[2] = sun_[0][j];
    double sun_light = 0.0, seen = 1.0;
    for (int k = 0; k < pieces; ++k) {
      st[0] = st[2];
      fw[0] = fw[2];
      em[0] = em[2];
      for (int p = 1; p < 3; ++p) {
        if (k == pieces - 1 && p == 2) {
          // The cell's own exit, read already (a point on the medium's box
          // would read as outside it there after rounding).
          st[2] = sigma_t_[2][j];
          fw[2] = forward_[2][j];
          em[2] = sun_[2][j];
          continue;
        }
        const double t = t0 + (k + 0.5 * p) * step;
        in_scattering_.medium_at(t, medium_point_);
        const std::vector<double>& ms = medium_point_.sigma_s;
        const std::vector<double>& mg = medium_point_.g;
        const double sa = lerp(medium_point_.sigma_a.data()), ss = lerp(ms.data());
        st[p] = sa + ss;
        sigma_s[j] = ss;
        g[j] = ss > 0.0 ? ((1.0 - lerp.frac) * ms[lerp.sample0] * mg[lerp.sample0] +
                           lerp.frac * ms[lerp.sample1] * mg[lerp.sample1]) /
                              ss
                        : 0.0;
        emissivity[j] = 0.0;
        in_scattering_.add_sun(cell, p, t, sigma_s.data(), g.data(), emissivity.data());
        fw[p] = forward_at(ss, g[j]);
        em[p] = emissivity[j];
      }
      const CellEmission c = integrate_seen(step, st, fw, em);
      sun_light += seen * c.emitted;
      seen *= c.transmittance;
    }
    radiance_[j] += (kKeepsForward ? attenuation_[j] : transmittance_[j]) * sun_light;
    // The rest over the whole cell.
    const double smooth[3] = {emissivity_[0][j] - sun_[0][j], emissivity_[1][j] - sun_[1][j],
                              emissivity_[2][j] - sun_[2][j]};
    const double* cst[3] = {&sigma_t_[0][j], &sigma_t_[1][j], &sigma_t_[2][j]};
    const double* cfw[3] = {&forward_[0][j], &forward_[1][j], &forward_[2][j]};
    const double* csm[3] = {smooth, smooth + 1, smooth + 2};
    add(cell.t_end - cell.t_begin, 1, cst, cfw, csm, j);
  }

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
      forward_[p][j] = forward_at(ss, g[j]);
    }
    if constexpr (kCutsSteepCells)
      in_scattering_.add(cell, p, t, sigma_s.data(), g.data(), emissivity_[p].data(),
                         sun_[p].data());
    else
      in_scattering_.add(cell, p, t, sigma_s.data(), g.data(), emissivity_[p].data());
  }

  const SpectralNodes& nodes_;
  int count_;
  InScattering& in_scattering_;
  double* radiance_;
  double* transmittance_;
  double* attenuation_;
  std::array<NodeArray, 3> sigma_t_{}, forward_{}, emissivity_{};
  std::array<NodeArray, 3> sun_{};  // σs J_sun (kCutsSteepCells)
  MediumPoint medium_point_;        // cut_cell's
  bool have_exit_ = false;
  std::uint64_t cells_ = 0;
};

}  // namespace obscura
