#pragma once
// Clouds made from formulas, in the layout the lattice march reads
// (obscura/render/lattice/lattice_view.h), for the GPU check: no file
// formats, no medium classes, nothing but the standard library, so that it
// builds on a bare GPU machine. A cloud is a sum of Gaussian lobes of
// density ρ on a voxel grid, laid out as obscura lays a grid cloud out: one
// lattice node per voxel centre plus a rim node each side that repeats the
// edge voxel, in blocks of 8³ nodes held only where the cloud is within a
// node of them. Per spectral node: σa = ρ σa_peak, σs = ρ σs_peak, g, and
// T = T_ambient + ΔT ρ/ρ_peak; with light, V_sun (0 below a shadow height)
// and smooth synthetic spherical-harmonic coefficients; τ_sun is left zero
// for the sun kernel to fill.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "obscura/core/mat3.h"
#include "obscura/core/planck_table.h"
#include "obscura/core/vec3.h"
#include "obscura/gpu/lattice_executor.h"

namespace obscura::gpu_check {

struct Lobe {
  Vec3 centre_m;
  double sigma_m = 1.0;
  double weight = 1.0;
};

struct CloudSpec {
  std::array<int, 3> voxels{64, 64, 64};
  double voxel_m = 1.0;
  Vec3 origin_m;                     // the grid's minimum corner
  Mat3 rotation = Mat3::identity();  // grid axes in the world
  std::vector<Lobe> lobes;
  double cutoff = 0.0;  // ρ below this fraction of the peak is zero (0: the cloud fills the grid)
  std::vector<double> wavelengths_um;              // one record set per wavelength
  std::vector<double> peak_sigma_a, peak_sigma_s;  // per wavelength, 1/m
  double g = 0.5;
  double ambient_k = 290.0, excess_k = 30.0;
  int sh_degree = -1;              // −1: medium records only
  double shadow_below_m = -1e300;  // V_sun = 0 below this world height
  double sh_amplitude = 1.0;       // c_00 scale, W m⁻² µm⁻¹
};

class ProceduralCloud {
 public:
  explicit ProceduralCloud(const CloudSpec& spec);

  // What an executor loads (pointers into this cloud).
  FrameLattice frame() const;
  const CloudSpec& spec() const { return spec_; }
  int stride() const { return stride_; }
  std::uint64_t slots() const { return blocks_.size() * LatticeView::kBlockNodes; }
  std::uint64_t record_bytes() const;
  // The world box the grid covers (its 8 corners' bounds).
  Vec3 centre_m() const;

 private:
  CloudSpec spec_;
  int stride_;
  LatticeView view_;
  std::vector<std::int32_t> block_index_;
  std::vector<std::array<int, 3>> blocks_;
  std::vector<std::uint8_t> occupied_;
  std::vector<std::vector<float>> records_;
  std::vector<std::unique_ptr<PlanckTable>> planck_;
};

}  // namespace obscura::gpu_check
