#pragma once
// The built-in smoke dispersion model (issue #6; docs/dispersion.md): the
// default data source of the preparation phase, standing in for CFD. Every
// device releases a train of Gaussian puffs that the wind carries and the
// Pasquill–Gifford σ of the chosen set spreads, reflected at the ground.
// Point queries here; gridded keyframes in dispersion_grid.h.
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/prep/dispersion/dispersion_config.h"
#include "obscura/prep/dispersion/puff_train.h"

namespace obscura {

class DispersionModel {
 public:
  // Validates the configuration (validate_dispersion_config) and releases
  // every device's puffs.
  explicit DispersionModel(DispersionConfig config);

  const DispersionConfig& config() const { return config_; }
  // All puffs, device by device in configuration order, each device's in
  // release order. This fixed order makes every sum over puffs deterministic.
  const std::vector<Puff>& puffs() const { return puffs_; }

  // Puffs released at or before `time_s`, in puffs() order, at that time.
  std::vector<PuffState> puffs_at(double time_s) const;

  // Aerosol mass released up to `time_s` (puffs whose release time has come), g.
  double released_mass_g(double time_s) const;

  // Σ over released puffs of puff_concentration_g_m3 (docs/domain.md §3.1), g/m³.
  double concentration_g_m3(const Vec3& point_m, double time_s) const;

  // T = T_ambient + Σ C_i ΔT_i / Σ C_i, K: the smoke at a point is a mix of
  // the puffs present, each puff's excess ΔT_i = ΔT0 exp(−age/τ) weighted by
  // its share of the concentration there (mixing of equal-heat-capacity air
  // parcels, a deliberately simple model: no radiative or buoyant exchange).
  // Where no smoke is present, T_ambient.
  double temperature_k(const Vec3& point_m, double time_s) const;

 private:
  DispersionConfig config_;
  std::vector<Puff> puffs_;
};

}  // namespace obscura
