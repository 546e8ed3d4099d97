#pragma once
// Canonical cases with known answers, run through the same transport code that
// renders images (the path tracer, tracking, the media): no case has a formula
// inside the solver. Each returns rows comparing an obtained Monte Carlo mean
// with its reference, with the standard error and a pass flag:
//   pass ⇔ |obtained − reference| ≤ max(3·stderr, tolerance·|reference|)
// and the standard error itself below tolerance·|reference| (enough samples to
// tell a `tolerance` bias apart from noise).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "obscura/scene/render_settings.h"

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
  bool judged = true;  // false: no reference for these parameters, obtained only
  double relative_error() const {
    return reference != 0 ? (obtained - reference) / reference : obtained;
  }
};

struct ValidationOptions {
  // Paths (or estimates) per quantity; 0: batches of `batch_samples` until
  // the standard error is below half the tolerance (at most 5e7).
  int samples = 0;
  // Draws per batch while sampling to the target (samples = 0): the first
  // batch is the fewest draws a quantity gets. Smaller batches stop nearer
  // the target, at the price of a rougher standard error where they stop.
  int batch_samples = 50000;
  // The solver and its settings (scene/render_settings.h), checked as a scene
  // file's are; settings.seed and settings.threads also drive the cases' own
  // sampling (results do not depend on the thread count). Monte Carlo methods
  // only, except emission–absorption on the cases without scattering
  // (emitting-slab, equilibrium with albedo 0). The photon map is judged at
  // 2 % at least (its density estimate is biased); the slab then needs a
  // finite --half-width (photons spread over the slab's whole width).
  RenderSettings settings = [] {
    RenderSettings s;
    s.method = RenderMethod::kPathTracer;
    return s;
  }();
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
std::vector<ValidationRow> validate_single_scatter(double tau, double g,
                                                   const ValidationOptions& o);
// Transmittance by ratio tracking through a voxelised Gaussian puff (128³) on
// three rays, against e^{−τ} with τ from the erf closed form.
std::vector<ValidationRow> validate_puff_transmittance(const ValidationOptions& o);

// Total reflectance R, total transmittance T (unscattered part included) and
// unscattered transmittance T_direct of a laterally infinite, index-matched,
// non-emitting slab of optical thickness τ, albedo and HG asymmetry g, lit by a
// collimated beam at zenith cosine μ0 or by isotropic diffuse radiance from
// above (docs/validation.md, "Slab reflectance and transmittance").
enum class SlabIncidence { kCollimated, kDiffuse };

struct SlabSpec {
  double albedo = 0.9, tau = 1.0, g = 0.5;
  SlabIncidence incidence = SlabIncidence::kCollimated;
  double mu0 = 1.0;           // collimated only; 1: normal incidence
  double half_width_m = 1e6;  // the slab is 1 m thick and ±half_width wide
};

struct SlabReference {
  double r = 0, t = 0, t_direct = 0;
  std::string source;
};

// The row of a slab table (data/validation/slab_reference.csv: albedo, tau, g,
// incidence, R_total, T_total, T_unscattered, source) for these parameters, the
// converged DISORT row when there is one; nullopt when none matches. Throws
// InputError naming the file and line for a malformed table.
std::optional<SlabReference> find_slab_reference(const std::string& csv_path, const SlabSpec& slab);

// Rows R, T and T_direct. R and T are judged against `reference` (within 1 %
// or 3 standard errors) when given and non-zero, else reported unjudged;
// T_direct is judged against its closed form, e^{−τ/μ0} or 2 E3(τ).
std::vector<ValidationRow> validate_slab(const SlabSpec& slab,
                                         const std::optional<SlabReference>& reference,
                                         const ValidationOptions& o);

}  // namespace obscura
