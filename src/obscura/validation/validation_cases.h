#pragma once
// Canonical cases with known answers, run through the same transport code that
// renders images (the path tracer, tracking, the media): no case has a formula
// inside the solver. Each returns rows comparing an obtained Monte Carlo mean
// with its reference, with the standard error and a pass flag:
//   pass ⇔ |obtained − reference| ≤ max(3·stderr, tolerance·|reference|)
// and the standard error itself below tolerance·|reference| (enough samples to
// tell a `tolerance` bias apart from noise).
#include <cstdint>
#include <string>
#include <vector>

namespace obscura {

struct ValidationRow {
  std::string case_name;
  std::string quantity;
  double reference = 0;
  double obtained = 0;
  double stderr_mean = 0;
  double tolerance = 0;  // relative
  bool pass = false;
  long long samples = 0;
  double relative_error() const { return reference != 0 ? (obtained - reference) / reference : obtained; }
};

struct ValidationOptions {
  // Paths (or estimates) per quantity; 0: batches of 50 000 until the standard
  // error is below half the tolerance (at most 5e7).
  int samples = 0;
  std::uint64_t seed = 1;
};

// White furnace: a conservative (albedo 1) cube of optical side τ and
// asymmetry g inside uniform radiance L0 (a 300 K sky at 10 µm): L = L0.
std::vector<ValidationRow> validate_furnace(double tau, double g, const ValidationOptions& o);
// Thermal equilibrium: a cube of albedo A, optical side τ, asymmetry g, at T,
// over a grey ground at T under a sky at T: L = B(T) at 4 µm.
std::vector<ValidationRow> validate_equilibrium(double albedo, double tau, double g,
                                                double temperature_k, const ValidationOptions& o);
// Isothermal absorbing slab of optical thickness τ at T over a 0 K background,
// seen along its normal: L = B(T)(1 − e^{−τ}) at 10 µm.
std::vector<ValidationRow> validate_emitting_slab(double tau, double temperature_k,
                                                  const ValidationOptions& o);
// Single scattering of sunlight (elevation 50°) in an optically thin
// conservative slab seen from below: closed form (docs/physics.md).
std::vector<ValidationRow> validate_single_scatter(double tau, double g, const ValidationOptions& o);
// Transmittance by ratio tracking through a voxelised Gaussian puff (128³) on
// three rays, against e^{−τ} with τ from the erf closed form.
std::vector<ValidationRow> validate_puff_transmittance(const ValidationOptions& o);

}  // namespace obscura
