#pragma once
// The obscurant materials database (data/materials/*.json, docs/materials.md):
// what one obscurant is optically, with the source of every number, and its
// bulk coefficients at a wavelength and relative humidity.
//
// Three kinds of material, chosen by what has been published (docs/domain.md §2):
//   "mie"        spheres of a tabulated complex refractive index, density and
//                lognormal size distribution: bulk_optics (size_distribution.h)
//                with n and k interpolated linearly in wavelength; hygroscopic
//                droplets grow with humidity (Raoult's law, volume mixing with
//                water). Wavelengths outside the index table may be covered by
//                tabulated bands.
//   "tabulated"  mass coefficients by band or wavelength from the literature,
//                not from Mie (cited ranges are kept as ranges).
//   "thin-flake" randomly oriented opaque flakes: α_ext = 1/(ρ t) (docs/domain.md
//                §2.4); ω and g from the large-particle limit with the
//                measured index, when the file gives one.
// Coefficients are in m²/g of the material's mass basis (Material::mass_basis).
#include <complex>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "obscura/optics/size_distribution.h"

namespace obscura {

// A number from the literature: a value, or a cited range whose midpoint is
// the nominal value (docs/domain.md §6.4: expose ranges, not constants).
struct CitedValue {
  double value = 0;  // nominal: the given value, or (min + max) / 2
  double min = 0, max = 0;
  bool is_range() const { return min != max; }
};

// Complex refractive index m = n + ik (k ≥ 0 absorbing) against vacuum
// wavelength, interpolated linearly in wavelength between rows.
struct RefractiveIndexTable {
  std::vector<double> wavelength_um, n, k;  // wavelengths strictly increasing
  std::string source;
};

// m at a wavelength inside the table (linear in wavelength between rows).
// Throws InputError (field "wavelength_um") outside it: no extrapolation.
std::complex<double> refractive_index_at(const RefractiveIndexTable& table, double wavelength_um);

// Mass coefficients over a band [lo, hi] (lo == hi: one wavelength), not
// from Mie. Albedo and asymmetry are absent where no source gives them.
struct TabulatedBand {
  double lo_um = 0, hi_um = 0;
  CitedValue mass_extinction_m2_g;
  std::optional<CitedValue> albedo, asymmetry;
  std::string source, note;
};

struct TabulatedOptics {
  std::string note;                  // says where the values come from and that they are not Mie
  std::vector<TabulatedBand> bands;  // increasing, not overlapping
};

// Water uptake of a hygroscopic solution droplet (phosphorus smoke): above
// the humidity at which the reference solution is in equilibrium, the
// droplet takes up water until its water activity equals the relative
// humidity (flat-surface equilibrium; the Kelvin term is neglected), by
// Raoult's law for an ideal solution with van 't Hoff factor i:
//   RH = n_w / (n_w + i n_s),  so  water per solute mass = (M_w/M_s) i RH/(1 − RH).
// Volumes add (no contraction on mixing): density, and n and k, are
// volume-weighted between the reference solution and water, and every
// radius grows by the cube root of the volume ratio (σ_g unchanged). Below
// that humidity the droplet keeps its reference composition.
struct HumidityGrowth {
  double reference_solute_mass_fraction = 0;  // solute mass / droplet mass at the reference
  double solute_molar_mass_g_mol = 0;
  double water_molar_mass_g_mol = 0;
  double van_t_hoff_factor = 0;
  double water_density_g_cm3 = 0;
  RefractiveIndexTable water_index;
  std::string source;
};

struct MieModel {
  RefractiveIndexTable index;
  double density_g_cm3 = 0;
  std::string density_source;
  LognormalDistribution distribution;  // at the reference (dry) state
  std::string distribution_source;
  std::optional<HumidityGrowth> humidity;
};

// α_ext = 1/(ρ t̄) with t̄ the mean thickness (docs/domain.md §2.4): a population
// of equal-area flakes of thicknesses t_i has area/mass = 1/(ρ mean t).
struct ThinFlakeModel {
  CitedValue thickness_um;
  double density_g_cm3 = 0;
  std::optional<CitedValue> diameter_um;      // for the range check diameter > λ
  std::optional<RefractiveIndexTable> index;  // for ω, g and the opacity check
  std::string source;
};

enum class MaterialKind { mie, tabulated, thin_flake };
const char* to_string(MaterialKind kind);

struct Material {
  std::string name, description, mass_basis;
  MaterialKind kind = MaterialKind::tabulated;
  std::vector<std::string> notes;
  std::optional<MieModel> mie;
  std::optional<ThinFlakeModel> flake;
  std::optional<TabulatedOptics> tabulated;  // kind tabulated, or beyond a Mie index table
  std::string file;                          // where it was read from
};

// Reads and validates a material file. Throws InputError naming the file and
// the JSON path ("/refractive_index/wavelength_um_n_k/3/2") for syntax errors,
// unknown or missing keys, a missing or empty "source", wavelengths that do
// not increase, n ≤ 0, k < 0, densities or sizes ≤ 0, fractions outside
// (0, 1], albedo outside [0, 1], |g| > 1, min > max, overlapping bands.
Material load_material(const std::filesystem::path& file);

// A material by name: data_directory()/materials/NAME.json, then ./NAME.json;
// an argument naming an existing file (or ending in .json) is read as a path.
// Throws InputError (field "material") naming what was looked for.
Material load_material_by_name(const std::string& name_or_path);

struct MaterialEntry {
  std::string name, description, kind;
  std::filesystem::path file;
};
// The shipped materials (data_directory()/materials/*.json), sorted by name.
std::vector<MaterialEntry> list_materials();

// (what, source) for every sourced block of the material, in file order.
std::vector<std::pair<std::string, std::string>> material_sources(const Material& material);

// State of a hygroscopic droplet at a relative humidity.
struct HumidityState {
  double relative_humidity = 0;
  double solute_mass_fraction = 0;   // in the grown droplet
  double mass_factor = 1;            // droplet mass per gram of reference mass (≥ 1)
  double radius_growth = 1;          // radius / reference radius
  double water_volume_fraction = 0;  // water added, as a fraction of the droplet volume
  double density_g_cm3 = 0;          // of the grown droplet
};
// Throws InputError (field "relative_humidity") unless 0 ≤ RH < 1.
HumidityState humidity_state(const MieModel& mie, double relative_humidity);

struct MaterialOptics {
  double wavelength_um = 0, relative_humidity = 0;
  // Per gram of the material's mass basis. For hygroscopic droplets that is
  // the reference (dry) mass: per gram of grown droplets divide by
  // hydrated_mass_factor. NaN where the sources give no albedo or asymmetry
  // (tabulated bands): scattering, absorption, albedo and g are then unknown.
  double mass_extinction_m2_g = 0;
  double mass_scattering_m2_g = 0;
  double mass_absorption_m2_g = 0;
  double single_scattering_albedo = 0;
  double asymmetry = 0;
  // The cited range of α_ext (equal to the value where there is none).
  double mass_extinction_min_m2_g = 0, mass_extinction_max_m2_g = 0;
  double hydrated_mass_factor = 1;
  std::string method;  // "mie", "tabulated", "tabulated (interpolated between bands)", "thin-flake"
  std::string note;    // caveats at this wavelength, or ""
};

// Coefficients at one vacuum wavelength (µm). Throws InputError naming the
// material file and "wavelength_um" where the material has no data, and
// "relative_humidity" unless 0 ≤ RH < 1.
MaterialOptics optics_at(const Material& material, double wavelength_um,
                         double relative_humidity = 0);

// The same at many wavelengths, in parallel over wavelengths (0: all cores);
// the result is the same for any thread count.
std::vector<MaterialOptics> optics_at(const Material& material,
                                      std::span<const double> wavelengths_um,
                                      double relative_humidity = 0, int threads = 0);

// Fresnel reflectance of a flat interface from air into index m, averaged
// over random orientations (weight 2 cosθ sinθ dθ, the share of projected
// area at incidence θ), and the asymmetry of the reflected light (scattering
// angle π − 2θ). Used for thin flakes.
struct RandomFacetReflection {
  double reflectance = 0, asymmetry = 0;
};
RandomFacetReflection random_facet_reflection(std::complex<double> m);

}  // namespace obscura
