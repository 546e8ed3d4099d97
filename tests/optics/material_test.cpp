// The materials database (data/materials/*.json, docs/materials.md): every
// shipped file loads; its measured index tables carry the source values; the
// mass extinction of every shipped obscurant lies in docs/domain.md §2.2's cited
// ranges at the band centres; phosphorus smoke grows with humidity; thin flakes
// follow docs/domain.md §2.4; bad files name the file and the JSON path.
#include "obscura/optics/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "obscura/core/data_directory.h"
#include "obscura/core/error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

// The band centres of docs/domain.md §2.2's columns: visible, Nd:YAG, MWIR, LWIR.
constexpr double kVisible = 0.55, kYag = 1.064, kMwir = 4.0, kLwir = 10.0;

Material shipped(const std::string& name) {
  return load_material(data_directory() / "materials" / (name + ".json"));
}

TEST(Material, EveryShippedFileLoadsAndCitesItsSources) {
  const auto entries = list_materials();
  std::set<std::string> names;
  for (const auto& e : entries) {
    SCOPED_TRACE(e.file.string());
    names.insert(e.name);
    EXPECT_EQ(e.name, e.file.stem().string()) << "load_material_by_name finds a file by its name";
    EXPECT_FALSE(e.description.empty());
    const Material m = load_material(e.file);
    EXPECT_FALSE(m.mass_basis.empty());
    const auto sources = material_sources(m);
    EXPECT_FALSE(sources.empty());
    for (const auto& [what, source] : sources) EXPECT_GT(source.size(), 20u) << what;
  }
  const std::set<std::string> expected{"aluminium_flakes", "brass_flakes",    "fog_oil",
                                       "graphite_flakes",  "graphite_powder", "hc_smoke",
                                       "phosphorus_smoke", "soil_dust",       "soot",
                                       "water_fog",        "water_fog_fine"};
  EXPECT_EQ(names, expected);
}

// Every Mie material over its whole index table, on a grid: the coefficients
// are consistent (α_ext = α_sca + α_abs, 0 ≤ ω ≤ 1, |g| ≤ 1), in parallel and
// serially alike.
TEST(Material, MieMaterialsAreConsistentOverTheirTables) {
  for (const auto* name : {"water_fog", "water_fog_fine", "soot", "fog_oil", "phosphorus_smoke"}) {
    SCOPED_TRACE(name);
    const Material m = shipped(name);
    const auto& w = m.mie->index.wavelength_um;
    std::vector<double> grid;
    for (int i = 0; i <= 12; ++i)
      grid.push_back(w.front() * std::pow(w.back() / w.front(), i / 12.0));
    grid.back() = w.back();  // exactly, despite rounding in pow
    const auto parallel = optics_at(m, grid, 0.0, 0);
    const auto serial = optics_at(m, grid, 0.0, 1);
    ASSERT_EQ(parallel.size(), grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const MaterialOptics& o = parallel[i];
      SCOPED_TRACE(grid[i]);
      EXPECT_EQ(o.method, "mie");
      EXPECT_GT(o.mass_extinction_m2_g, 0.0);
      EXPECT_NEAR(o.mass_scattering_m2_g + o.mass_absorption_m2_g, o.mass_extinction_m2_g,
                  1e-12 * o.mass_extinction_m2_g);
      EXPECT_GE(o.single_scattering_albedo, 0.0);
      EXPECT_LE(o.single_scattering_albedo, 1.0);
      EXPECT_LE(std::abs(o.asymmetry), 1.0);
      EXPECT_EQ(o.mass_extinction_m2_g, serial[i].mass_extinction_m2_g);
      EXPECT_EQ(o.asymmetry, serial[i].asymmetry);
      EXPECT_EQ(o.mass_extinction_m2_g, optics_at(m, grid[i]).mass_extinction_m2_g);
    }
  }
}

// Rows typed from the refractiveindex.info files in
// ../shared/data/refractive-index/ (line numbers in brackets): the converted
// tables hold them exactly.
TEST(Material, IndexTablesHoldTheSourceRows) {
  struct Row {
    const char* material;
    bool flake;
    double wavelength, n, k;
  };
  const std::vector<Row> rows{
      {"water_fog", false, 0.55, 1.333, 1.96e-9},  // main_H2O_nk_Hale.yml [line 29]
      {"water_fog", false, 4.0, 1.351, 0.00460},   // [78]
      {"water_fog", false, 10.0, 1.218, 0.0508},   // [128]
      {"water_fog", false, 0.3, 1.349, 1.60e-8},   // first row kept [19]
      {"water_fog", false, 14.0, 1.210, 0.370},    // last row kept [136]
      {"soot", false, 4.0, 2.076, 0.326},   // other_soots_diesel_soot_nk_Querry-NMSU.yml [199]
      {"soot", false, 10.0, 2.292, 0.363},  // [274]
      {"graphite_flakes", true, 0.55, 1.652, 0.853},  // main_C_nk_Querry-AsburyMicro260.yml [46]
      {"graphite_flakes", true, 10.0, 4.791, 3.513},  // [541]
      {"brass_flakes", true, 0.55, 0.527, 2.765},  // other_alloys_Cu-Zn_nk_Querry-Cu70Zn30.yml [46]
      {"brass_flakes", true, 10.0, 16.878, 51.601},     // [540]
      {"brass_flakes", true, 14.0845, 24.982, 66.833},  // first row at or above 14 µm [569]
  };
  for (const auto& r : rows) {
    SCOPED_TRACE(std::string(r.material) + " " + std::to_string(r.wavelength));
    const Material m = shipped(r.material);
    const RefractiveIndexTable& t = r.flake ? *m.flake->index : m.mie->index;
    const auto m_at = refractive_index_at(t, r.wavelength);
    EXPECT_EQ(m_at.real(), r.n);
    EXPECT_EQ(m_at.imag(), r.k);
    EXPECT_NE(t.source.find("refractiveindex.info"), std::string::npos);
  }
  // The phosphorus-smoke file carries the same water table for its growth rule.
  EXPECT_EQ(shipped("phosphorus_smoke").mie->humidity->water_index.n,
            shipped("water_fog").mie->index.n);
  // Tables cover 0.3–14 µm and no more than one row beyond each end.
  for (const auto* name : {"water_fog", "soot"}) {
    const Material m = shipped(name);
    const auto& w = m.mie->index.wavelength_um;
    EXPECT_LE(w.front(), 0.3);
    EXPECT_GE(w.back(), 14.0);
    EXPECT_GE(w[1], 0.3) << name;
    EXPECT_LT(w[w.size() - 2], 14.0) << name;
  }
}

// Between rows the index is linear in wavelength. docs/domain.md §2.5 quotes
// values interpolated from the same files; they are reproduced to their
// printed digits.
TEST(Material, InterpolatedIndicesMatchDomainTable) {
  struct Value {
    const char* material;
    bool flake;
    double wavelength, n, k, n_tol, k_tol;
  };
  const std::vector<Value> values{
      {"water_fog", false, 1.064, 1.326, 5.1e-6, 5e-4, 5e-8},
      {"water_fog", false, 10.6, 1.179, 0.072, 5e-4, 5e-4},
      {"soot", false, 0.55, 1.61, 0.28, 5e-3, 5e-3},
      {"soot", false, 1.064, 1.76, 0.32, 5e-3, 5e-3},
      {"soot", false, 10.6, 2.29, 0.35, 5e-3, 5e-3},
      {"graphite_flakes", true, 1.064, 1.890, 1.28, 5e-4, 5e-3},
      {"graphite_flakes", true, 10.6, 4.89, 3.60, 5e-3, 5e-3},
      {"brass_flakes", true, 1.064, 0.65, 6.82, 5e-3, 5e-3},
      {"brass_flakes", true, 10.6, 18.1, 54.0, 5e-2, 5e-2},
  };
  for (const auto& v : values) {
    SCOPED_TRACE(std::string(v.material) + " " + std::to_string(v.wavelength));
    const Material m = shipped(v.material);
    const auto x = refractive_index_at(v.flake ? *m.flake->index : m.mie->index, v.wavelength);
    EXPECT_NEAR(x.real(), v.n, v.n_tol);
    EXPECT_NEAR(x.imag(), v.k, v.k_tol);
  }
  // Hale & Querry rows 10.5 µm (1.185, 0.0662) and 11.0 µm (1.153, 0.0968).
  const auto w = refractive_index_at(shipped("water_fog").mie->index, 10.6);
  EXPECT_NEAR(w.real(), 1.185 + 0.2 * (1.153 - 1.185), 1e-12);
  EXPECT_NEAR(w.imag(), 0.0662 + 0.2 * (0.0968 - 0.0662), 1e-12);
  EXPECT_THROW(refractive_index_at(shipped("fog_oil").mie->index, 0.5), InputError);
}

// The key physical check: α_ext (m²/g) of each shipped obscurant at the band
// centres against docs/domain.md §2.2. [U] literature ranges (EOSAEL/COMBIC and
// smoke-week literature) must contain the value; where §2.2 gives its own
// Mie value [D] for the same model, the value must agree with it within the
// stated tolerance (half a unit of the printed digit, or a few per cent where
// the inputs behind §2.2 are not fully stated).
struct Expectation {
  const char* material;
  double wavelength;
  double lo, hi;  // interval that must contain α_ext
  const char* source;
};

TEST(Material, MassExtinctionWithinDomainRanges) {
  const std::vector<Expectation> cases{
      // WP/RP smoke: [U] 3–5, 1–2.5, 0.2–0.5, 0.2–0.5.
      {"phosphorus_smoke", kVisible, 3, 5, "§2.2 WP/RP 0.4–0.7 µm [U]"},
      {"phosphorus_smoke", kVisible, 3.75, 3.95, "§2.2/§2.3 [D] 3.8 (MMD 0.5) – 3.9 (MMD 0.7)"},
      {"phosphorus_smoke", kYag, 1, 2.5, "§2.2 WP/RP 1.06 µm [U]"},
      {"phosphorus_smoke", kYag, 1.05, 1.65, "§2.2 [D] 1.1–1.6"},
      {"phosphorus_smoke", kMwir, 0.2, 0.5, "§2.2 WP/RP 3–5 µm [U]"},
      {"phosphorus_smoke", kLwir, 0.2, 0.5, "§2.2 WP/RP 8–12 µm [U]"},
      // Fog oil: [U] 5–8, 2–4, 0.1–0.3, 0.01–0.05; [D] 7.6–7.9, 2.4–3.4.
      {"fog_oil", kVisible, 5, 8, "§2.2 fog oil 0.4–0.7 µm [U]"},
      {"fog_oil", kVisible, 7.55, 7.95, "§2.2 [D] 7.6–7.9 (MMD 0.5–0.7 µm)"},
      {"fog_oil", kYag, 2, 4, "§2.2 fog oil 1.06 µm [U]"},
      {"fog_oil", kYag, 2.35, 3.45, "§2.2 [D] 2.4–3.4"},
      {"fog_oil", kMwir, 0.1, 0.3, "§2.2 fog oil 3–5 µm [U]"},
      {"fog_oil", kLwir, 0.01, 0.05, "§2.2 fog oil 8–12 µm [U]"},
      // HC: [U] 3–4.5, 1–2, 0.05–0.2, 0.02–0.1.
      {"hc_smoke", kVisible, 3, 4.5, "§2.2 HC [U]"},
      {"hc_smoke", kYag, 1, 2, "§2.2 HC [U]"},
      {"hc_smoke", kMwir, 0.05, 0.2, "§2.2 HC [U]"},
      {"hc_smoke", kLwir, 0.02, 0.1, "§2.2 HC [U]"},
      // Graphite powder: 1–2 flat [U]; 1.02 (3.7–4.8 µm), 1.01 (7.5–14 µm) [S] Shi 2020.
      {"graphite_powder", kVisible, 1, 2, "§2.2 graphite [U]"},
      {"graphite_powder", kYag, 1, 2, "§2.2 graphite [U]"},
      {"graphite_powder", kMwir, 1.02, 1.02, "§2.2 Shi 2020 [S]"},
      {"graphite_powder", kLwir, 1.01, 1.01, "§2.2 Shi 2020 [S]"},
      // Aluminium: 1.78 (3–5 µm), 2.01 (8–12 µm) [S] Shi 2020.
      {"aluminium_flakes", kMwir, 1.78, 1.78, "§2.2 Shi 2020 [S]"},
      {"aluminium_flakes", kLwir, 2.01, 2.01, "§2.2 Shi 2020 [S]"},
      // Graphite flakes 0.1 µm thick: flake rule 4.5 (§2.4 table), under the
      // ~5 m²/g computed upper limit of Liu 2021 [S].
      {"graphite_flakes", kVisible, 4.45, 4.55, "§2.4 table, t = 0.1 µm: 4.5"},
      {"graphite_flakes", kLwir, 0, 5, "§2.2 Liu 2021 upper limit ~5"},
      // Brass flakes: the flake rule over 0.08–0.32 µm gives 0.37–1.5 [D]
      // (§2.2, §2.4); the nominal value (mean thickness 0.2 µm: 0.59, §2.4
      // table) lies below the [U] ~1–1.5, which the range reaches.
      {"brass_flakes", kVisible, 0.585, 0.595, "§2.4 table, t = 0.2 µm: 0.59"},
      {"brass_flakes", kVisible, 0.365, 1.5, "§2.2 flake rule 0.37–1.5 [D]"},
      {"brass_flakes", kLwir, 0.365, 1.5, "§2.2 flake rule 0.37–1.5 [D]"},
      // Soot spheres: [D] 4.4, 1.7, 0.27, 0.10 (inputs not stated in
      // docs/domain.md, see soot.json): within 5 %; and below the measured
      // 8.7 m²/g of flaming soot [S] (Mie spheres underestimate aggregates).
      {"soot", kVisible, 4.4 * 0.95, 4.4 * 1.05, "§2.2 soot [D] 4.4"},
      {"soot", kVisible, 0, 8.7, "§2.1 FDS flaming soot 8.7 [S]"},
      {"soot", kYag, 1.7 * 0.95, 1.7 * 1.05, "§2.2 soot [D] 1.7"},
      {"soot", kMwir, 0.27 * 0.95, 0.27 * 1.05, "§2.2 soot [D] 0.27"},
      {"soot", kLwir, 0.10 * 0.95, 0.10 * 1.05, "§2.2 soot [D] 0.10"},
      // Natural fog, MMD 10 µm: [D] 0.35, 0.37, 0.50, 0.17, within 5 %.
      {"water_fog", kVisible, 0.35 * 0.95, 0.35 * 1.05, "§2.2 water fog [D] 0.35"},
      {"water_fog", kYag, 0.37 * 0.95, 0.37 * 1.05, "§2.2 water fog [D] 0.37"},
      {"water_fog", kMwir, 0.50 * 0.95, 0.50 * 1.05, "§2.2 water fog [D] 0.50"},
      {"water_fog", kLwir, 0.17 * 0.95, 0.17 * 1.05, "§2.2 water fog [D] 0.17"},
      // Artificial fine fog, MMD 3 µm: [D] 1.37, 1.65, 0.58, 0.09, half a unit.
      {"water_fog_fine", kVisible, 1.365, 1.375, "§2.2 fine fog [D] 1.37"},
      {"water_fog_fine", kYag, 1.645, 1.655, "§2.2 fine fog [D] 1.65"},
      {"water_fog_fine", kMwir, 0.575, 0.585, "§2.2 fine fog [D] 0.58"},
      {"water_fog_fine", kLwir, 0.085, 0.095, "§2.2 fine fog [D] 0.09"},
      // Soil dust: [U] 0.2–1 visible; [D] 0.18–0.24 and 0.20–0.34 (kaolinite).
      {"soil_dust", kVisible, 0.2, 1, "§2.2 dust [U]"},
      {"soil_dust", kMwir, 0.18, 0.24, "§2.2 dust [D]"},
      {"soil_dust", kLwir, 0.20, 0.34, "§2.2 dust [D]"},
  };
  std::map<std::string, Material> materials;
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.material) + " at " + std::to_string(c.wavelength) + " µm, " +
                 c.source);
    if (!materials.count(c.material)) materials.emplace(c.material, shipped(c.material));
    const MaterialOptics o = optics_at(materials.at(c.material), c.wavelength);
    EXPECT_GE(o.mass_extinction_m2_g, c.lo - 1e-12);
    EXPECT_LE(o.mass_extinction_m2_g, c.hi + 1e-12);
    EXPECT_GE(o.mass_extinction_m2_g, o.mass_extinction_min_m2_g);
    EXPECT_LE(o.mass_extinction_m2_g, o.mass_extinction_max_m2_g);
  }
  // Where docs/domain.md §2.2 gives albedo or asymmetry for the same model.
  EXPECT_NEAR(optics_at(shipped("soot"), kVisible).single_scattering_albedo, 0.29, 0.01);
  EXPECT_LT(optics_at(shipped("soot"), kMwir).single_scattering_albedo, 0.02);  // ω ≈ 0
  const Material fog = shipped("water_fog");
  EXPECT_NEAR(optics_at(fog, kVisible).asymmetry, 0.85, 0.01);           // g ≈ 0.85
  EXPECT_GT(optics_at(fog, kVisible).single_scattering_albedo, 0.9999);  // ω = 1
  const MaterialOptics fog_mwir = optics_at(fog, kMwir), fog_lwir = optics_at(fog, kLwir);
  EXPECT_GE(fog_mwir.single_scattering_albedo, 0.9);  // ω 0.9–0.95 (0.954)
  EXPECT_LE(fog_mwir.single_scattering_albedo, 0.955);
  EXPECT_NEAR(fog_mwir.asymmetry, 0.8, 0.01);           // g ≈ 0.8
  EXPECT_GE(fog_lwir.single_scattering_albedo, 0.595);  // ω 0.6–0.7 (0.5996)
  EXPECT_LE(fog_lwir.single_scattering_albedo, 0.7);
  EXPECT_GE(fog_lwir.asymmetry, 0.8);  // g 0.8–0.9
  EXPECT_LE(fog_lwir.asymmetry, 0.9);
  EXPECT_NEAR(optics_at(shipped("water_fog_fine"), kLwir).single_scattering_albedo, 0.26, 0.005);
  const MaterialOptics wp = optics_at(shipped("phosphorus_smoke"), kVisible);
  EXPECT_GT(wp.single_scattering_albedo, 0.9999);  // ω ≈ 1
  EXPECT_GE(wp.asymmetry, 0.72);                   // g ≈ 0.72–0.75
  EXPECT_LE(wp.asymmetry, 0.75);
  const double wp_yag_g = optics_at(shipped("phosphorus_smoke"), kYag).asymmetry;
  EXPECT_GE(wp_yag_g, 0.6);  // g ≈ 0.6–0.7
  EXPECT_LE(wp_yag_g, 0.7);
  EXPECT_NEAR(optics_at(shipped("fog_oil"), kVisible).asymmetry, 0.70, 0.015);  // g ≈ 0.70
  // Cited ranges are carried: WP/RP LWIR 0.2–0.5, nominal the midpoint.
  const MaterialOptics wp_lwir = optics_at(shipped("phosphorus_smoke"), kLwir);
  EXPECT_EQ(wp_lwir.mass_extinction_min_m2_g, 0.2);
  EXPECT_EQ(wp_lwir.mass_extinction_max_m2_g, 0.5);
  EXPECT_DOUBLE_EQ(wp_lwir.mass_extinction_m2_g, 0.35);
  EXPECT_EQ(wp_lwir.method, "tabulated");
  EXPECT_TRUE(std::isnan(wp_lwir.single_scattering_albedo));  // not given by the source
  EXPECT_NEAR(optics_at(shipped("soil_dust"), kLwir).single_scattering_albedo, 0.45, 1e-12);
  // Aluminium has no visible value in docs/domain.md §2.2: no data, no invention.
  EXPECT_THROW(optics_at(shipped("aluminium_flakes"), kVisible), InputError);
}

// docs/domain.md §2.3 and §2.6: phosphorus smoke takes up water with RH; α per
// gram of dry agent rises with RH in the visible. The rule's yields per gram
// of phosphorus (3.16 / solute fraction) stay near the 3–8 quoted in §2.6.
TEST(Material, PhosphorusSmokeGrowsWithHumidity) {
  const Material m = shipped("phosphorus_smoke");
  const MieModel& mie = *m.mie;
  // Below the reference humidity (Raoult: 70 wt % acid at RH ≈ 0.70) nothing changes.
  for (double rh : {0.0, 0.5, 0.69}) {
    const HumidityState s = humidity_state(mie, rh);
    EXPECT_EQ(s.mass_factor, 1.0);
    EXPECT_EQ(s.radius_growth, 1.0);
    EXPECT_EQ(s.density_g_cm3, 1.6);
  }
  // Raoult with i = 1: water per acid mass = (18.015/97.994) RH/(1 − RH).
  const HumidityState s90 = humidity_state(mie, 0.9);
  const double ratio = 18.015 / 97.994 * 9.0;
  EXPECT_NEAR(s90.solute_mass_fraction, 1 / (1 + ratio), 1e-12);
  EXPECT_NEAR(s90.mass_factor, 0.7 * (1 + ratio), 1e-12);
  EXPECT_GT(s90.density_g_cm3, 1.0);
  EXPECT_LT(s90.density_g_cm3, 1.6);
  // Mass is conserved: grown volume × density = reference volume × ρ × factor.
  EXPECT_NEAR(std::pow(s90.radius_growth, 3) * s90.density_g_cm3, 1.6 * s90.mass_factor, 1e-12);
  for (double rh : {0.0, 0.7, 0.8, 0.9}) {
    const double yield = 3.16 / humidity_state(mie, rh).solute_mass_fraction;
    EXPECT_GE(yield, 3.0) << rh;
    EXPECT_LE(yield, 8.5) << rh;  // 8.4 at RH 0.9 against "roughly 3–8"
  }
  // α per gram of dry (reference) smoke in the visible rises with RH.
  double previous = optics_at(m, kVisible, 0.0).mass_extinction_m2_g;
  for (double rh : {0.75, 0.8, 0.85, 0.9, 0.95}) {
    const MaterialOptics o = optics_at(m, kVisible, rh);
    EXPECT_GT(o.mass_extinction_m2_g, previous) << rh;
    EXPECT_EQ(o.hydrated_mass_factor, humidity_state(mie, rh).mass_factor);
    previous = o.mass_extinction_m2_g;
  }
  // Humidity changes nothing for materials without a growth rule, and the
  // tabulated IR ranges say they ignore it.
  const Material fog = shipped("fog_oil");
  EXPECT_EQ(optics_at(fog, kVisible, 0.9).mass_extinction_m2_g,
            optics_at(fog, kVisible, 0.0).mass_extinction_m2_g);
  EXPECT_NE(optics_at(m, kLwir, 0.9).note.find("humidity"), std::string::npos);
  try {
    optics_at(m, kVisible, 1.0);
    ADD_FAILURE() << "RH = 1 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "relative_humidity");
  }
}

// Orientation-averaged Fresnel reflectance, against an independent
// integration over the angle of incidence with the textbook form
// cos θ_t = √(1 − sin²θ/m²) (Born & Wolf §1.5, §14.2 for complex m).
TEST(Material, RandomFacetReflection) {
  auto independent = [](std::complex<double> m) {
    const int n = 20000;
    double r_sum = 0, g_sum = 0;
    for (int i = 0; i < n; ++i) {
      const double theta = (i + 0.5) * (std::numbers::pi / 2) / n, c = std::cos(theta),
                   s = std::sin(theta);
      const std::complex<double> ct = std::sqrt(1.0 - s * s / (m * m));
      const double rs = std::norm((c - m * ct) / (c + m * ct));
      const double rp = std::norm((m * c - ct) / (m * c + ct));
      const double w = 0.5 * (rs + rp) * 2 * c * s * (std::numbers::pi / 2) / n;
      r_sum += w;
      g_sum += w * -std::cos(2 * theta);
    }
    return std::pair{r_sum, g_sum / r_sum};
  };
  for (const std::complex<double> m :
       {std::complex<double>(1.5, 0), {1.652, 0.853}, {16.878, 51.601}, {0.527, 2.765}}) {
    SCOPED_TRACE(m.real());
    const auto [r, g] = independent(m);
    const RandomFacetReflection f = random_facet_reflection(m);
    EXPECT_NEAR(f.reflectance, r, 1e-6);
    EXPECT_NEAR(f.asymmetry, g, 1e-5);
  }
  // Glass (n = 1.5) reflects 9.2 % of diffuse light.
  EXPECT_NEAR(random_facet_reflection({1.5, 0}).reflectance, 0.092, 0.001);
  EXPECT_NEAR(random_facet_reflection({1.0, 0}).reflectance, 0.0, 1e-15);
  // A near-perfect conductor reflects nearly all, with the isotropic-like g ≈ 0
  // of a mirror sphere.
  const RandomFacetReflection metal = random_facet_reflection({1e3, 1e3});
  EXPECT_GT(metal.reflectance, 0.99);
  EXPECT_NEAR(metal.asymmetry, 0.0, 0.01);
}

// docs/domain.md §2.4: α = 1/(ρ t) whatever the wavelength; ω between ½ (black)
// and 1 (mirror); caveats where the flakes are not wider than λ.
TEST(Material, ThinFlakeRule) {
  const Material brass = shipped("brass_flakes");
  const MaterialOptics vis = optics_at(brass, kVisible), lwir = optics_at(brass, kLwir);
  EXPECT_DOUBLE_EQ(vis.mass_extinction_m2_g, 1 / (8.5 * 0.2));
  EXPECT_DOUBLE_EQ(vis.mass_extinction_min_m2_g, 1 / (8.5 * 0.32));
  EXPECT_DOUBLE_EQ(vis.mass_extinction_max_m2_g, 1 / (8.5 * 0.08));
  EXPECT_EQ(lwir.mass_extinction_m2_g, vis.mass_extinction_m2_g);
  for (const auto& o : {vis, lwir}) {
    EXPECT_EQ(o.method, "thin-flake");
    EXPECT_GT(o.single_scattering_albedo, 0.5);
    EXPECT_LT(o.single_scattering_albedo, 1.0);
    EXPECT_GT(o.asymmetry, 0.0);
    EXPECT_LT(o.asymmetry, 1.0);
    EXPECT_NEAR(o.mass_scattering_m2_g + o.mass_absorption_m2_g, o.mass_extinction_m2_g, 1e-15);
  }
  // Brass is a good reflector in the IR.
  EXPECT_GT(lwir.single_scattering_albedo, vis.single_scattering_albedo);
  EXPECT_EQ(vis.note, "");
  EXPECT_NE(lwir.note.find("not wider than the wavelength"), std::string::npos);
  // Graphite at 0.1 µm: thinner than its absorption depth in the LWIR.
  EXPECT_NE(optics_at(shipped("graphite_flakes"), kLwir).note.find("absorption depth"),
            std::string::npos);
}

TEST(Material, TabulatedLookup) {
  const Material hc = shipped("hc_smoke");
  // Between the 1.064 µm point (1–2) and the 3–5 µm band (0.05–0.2): linear.
  const MaterialOptics mid = optics_at(hc, 2.032);
  EXPECT_EQ(mid.method, "tabulated (interpolated between bands)");
  EXPECT_NEAR(mid.mass_extinction_m2_g, 1.5 + 0.5 * (0.125 - 1.5), 1e-12);
  EXPECT_NEAR(mid.mass_extinction_min_m2_g, 1 + 0.5 * (0.05 - 1), 1e-12);
  // Inside a band: the band's value at its edges too.
  EXPECT_DOUBLE_EQ(optics_at(hc, 3.0).mass_extinction_m2_g, 0.125);
  EXPECT_DOUBLE_EQ(optics_at(hc, 12.0).mass_extinction_m2_g, 0.06);
  // No extrapolation, and no bridging between Mie and tabulated data.
  for (const auto& [name, lambda] :
       std::vector<std::pair<std::string, double>>{{"hc_smoke", 0.3},
                                                   {"hc_smoke", 13.0},
                                                   {"phosphorus_smoke", 2.0},
                                                   {"phosphorus_smoke", 0.4},
                                                   {"fog_oil", 14.0}}) {
    SCOPED_TRACE(name + " " + std::to_string(lambda));
    try {
      optics_at(shipped(name), lambda);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "wavelength_um");
      EXPECT_NE(e.file().find(name + ".json"), std::string::npos);
      EXPECT_NE(e.detail().find(name), std::string::npos);
    }
  }
}

class MaterialFileTest : public testing::TempDirTest {
 protected:
  // A small valid Mie material.
  static nlohmann::json valid() {
    return nlohmann::json::parse(R"({
      "name": "test_droplets", "description": "test", "kind": "mie", "mass_basis": "droplets",
      "refractive_index": {"source": "typed for the test",
                           "wavelength_um_n_k": [[0.5, 1.4, 0], [1.0, 1.4, 0.001], [2.0, 1.39, 0.01]]},
      "density_g_cm3": {"value": 1.2, "source": "typed for the test"},
      "size_distribution": {"type": "lognormal", "count_median_radius_um": 0.2,
                            "geometric_std": 1.5, "source": "typed for the test"}
    })");
  }
  fs::path write(const nlohmann::json& j, const std::string& name = "bad.json") {
    const fs::path p = dir_ / name;
    std::ofstream(p) << j.dump(2);
    return p;
  }
  // Loading `j` fails naming the file and `field`.
  void expect_error(const nlohmann::json& j, const std::string& field, const std::string& what) {
    const fs::path p = write(j);
    try {
      load_material(p);
      ADD_FAILURE() << "loaded: " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), p.string());
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_NE(e.detail().find(what), std::string::npos) << e.what();
    }
  }
};

TEST_F(MaterialFileTest, ValidFileLoads) {
  const Material m = load_material(write(valid()));
  EXPECT_EQ(m.name, "test_droplets");
  EXPECT_EQ(m.kind, MaterialKind::mie);
  EXPECT_GT(optics_at(m, 0.7).mass_extinction_m2_g, 0.0);
}

TEST_F(MaterialFileTest, BadFilesNameFileAndPath) {
  auto j = valid();
  j["colour"] = "grey";
  expect_error(j, "/colour", "unknown field");

  j = valid();
  j["refractive_index"]["wavelength_um_n_k"][2][0] = 0.9;
  expect_error(j, "/refractive_index/wavelength_um_n_k/2/0", "must increase");

  j = valid();
  j["refractive_index"]["wavelength_um_n_k"][1][2] = -0.1;
  expect_error(j, "/refractive_index/wavelength_um_n_k/1/2", "k must be >= 0");

  j = valid();
  j["refractive_index"]["wavelength_um_n_k"][0][1] = 0;
  expect_error(j, "/refractive_index/wavelength_um_n_k/0/1", "n must be > 0");

  j = valid();
  j["refractive_index"]["wavelength_um_n_k"][0] = {0.5, 1.4};
  expect_error(j, "/refractive_index/wavelength_um_n_k/0", "three numbers");

  j = valid();
  j["density_g_cm3"].erase("source");
  expect_error(j, "/density_g_cm3/source", "missing required field");

  j = valid();
  j["size_distribution"]["source"] = " ";
  expect_error(j, "/size_distribution/source", "source");

  j = valid();
  j["density_g_cm3"]["value"] = -1;
  expect_error(j, "/density_g_cm3/value", "> 0");

  j = valid();
  j["size_distribution"]["geometric_std"] = 1.0;
  expect_error(j, "/size_distribution/geometric_std", "> 1");

  j = valid();
  j["size_distribution"]["mass_median_diameter_um"] = 1.0;
  expect_error(j, "/size_distribution/mass_median_diameter_um", "exactly one");

  j = valid();
  j["kind"] = "fractal";
  expect_error(j, "/kind", "unknown kind");

  j = valid();
  j["tabulated"] = {
      {"note", "n"},
      {"bands", {{{"wavelength_um", {1.5, 3}}, {"mass_extinction_m2_g", 1}, {"source", "s"}}}}};
  expect_error(j, "/tabulated/bands/0/wavelength_um", "overlaps the refractive-index table");
}

TEST_F(MaterialFileTest, BadTabulatedAndFlakeFiles) {
  const auto tabulated = nlohmann::json::parse(R"({
    "name": "t", "description": "d", "kind": "tabulated", "mass_basis": "b",
    "tabulated": {"note": "not Mie", "bands": [
      {"wavelength_um": [3, 5], "mass_extinction_m2_g": {"min": 0.2, "max": 0.5}, "source": "s"},
      {"wavelength_um": [8, 12], "mass_extinction_m2_g": 0.3, "albedo": 0.4, "source": "s"}]}
  })");
  EXPECT_NO_THROW(load_material(write(tabulated)));
  auto j = tabulated;
  j["tabulated"]["bands"][1]["wavelength_um"] = {4, 12};
  expect_error(j, "/tabulated/bands/1/wavelength_um", "without overlapping");
  j = tabulated;
  j["tabulated"]["bands"][0]["mass_extinction_m2_g"] = {{"min", 0.5}, {"max", 0.2}};
  expect_error(j, "/tabulated/bands/0/mass_extinction_m2_g/max", "below min");
  j = tabulated;
  j["tabulated"]["bands"][1]["albedo"] = 1.2;
  expect_error(j, "/tabulated/bands/1/albedo", "in [0, 1]");
  j = tabulated;
  j["tabulated"]["bands"][1].erase("source");
  expect_error(j, "/tabulated/bands/1/source", "missing required field");
  j = tabulated;
  j["refractive_index"] = {{"source", "s"}};
  expect_error(j, "/refractive_index", "unknown field");

  const auto flake = nlohmann::json::parse(R"({
    "name": "f", "description": "d", "kind": "thin-flake", "mass_basis": "b",
    "flake": {"thickness_um": 0.1, "density_g_cm3": 2.0, "source": "s"}
  })");
  const Material f = load_material(write(flake));
  EXPECT_DOUBLE_EQ(optics_at(f, 1.0).mass_extinction_m2_g, 5.0);
  EXPECT_TRUE(std::isnan(optics_at(f, 1.0).asymmetry));  // no index: ω and g unknown
  j = flake;
  j["flake"]["thickness_um"] = 0;
  expect_error(j, "/flake/thickness_um", "> 0");
}

TEST_F(MaterialFileTest, LookupByName) {
  EXPECT_EQ(load_material_by_name("soot").name, "soot");
  const fs::path p = write(valid(), "my_smoke.json");
  EXPECT_EQ(load_material_by_name(p.string()).name, "test_droplets");
  // The current directory is searched after the shipped folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  const std::string name = load_material_by_name("my_smoke").name;
  fs::current_path(cwd);
  EXPECT_EQ(name, "test_droplets");
  try {
    load_material_by_name("no_such_smoke");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "material");
    EXPECT_NE(e.detail().find("no_such_smoke"), std::string::npos);
  }
  // A path that does not exist names the file.
  try {
    load_material_by_name((dir_ / "absent.json").string());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("absent.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace obscura
