// The compact species form expanded to spectral coefficients: sums over
// species worked by hand, g weighted by scattering, and bad input that names
// the species and the field.
#include "obscura/medium/species_optics.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "obscura/core/error.h"

namespace obscura {
namespace {

// Two species at two wavelengths on a 3×1×1 grid:
//   A: k_abs {0.5, 0.1}, k_sca {2.0, 0.0}, g {0.6, 0.0}   (A does not scatter at 10 µm)
//   B: k_abs {0.25, 0.3}, k_sca {1.0, 0.5}, g {-0.3, 0.2}
// Voxel 0 holds both (1 and 2 g/m³), voxel 1 nothing, voxel 2 only A (3 g/m³).
SpeciesCloud two_species() {
  SpeciesCloud c;
  c.dims = {3, 1, 1};
  c.placement.origin_m = {1, 2, 3};
  c.placement.voxel_size_m = 0.5;
  c.wavelengths_um = {0.55, 10.0};
  c.species = {{"A", {0.55, 10.0}, {0.5, 0.1}, {2.0, 0.0}, {0.6, 0.0}},
               {"B", {0.55, 10.0}, {0.25, 0.3}, {1.0, 0.5}, {-0.3, 0.2}}};
  c.concentration_g_m3 = {{1.0f, 0.0f, 3.0f}, {2.0f, 0.0f, 0.0f}};
  c.temperature_k = {300.0f, 288.0f, 350.0f};
  return c;
}

TEST(ExpandSpecies, SumsOverSpeciesWorkedByHand) {
  const VoxelGrid g = expand_species(two_species(), "test");
  ASSERT_EQ(g.dims(), (GridDims{3, 1, 1}));
  EXPECT_EQ(g.wavelengths_um(), (std::vector<double>{0.55, 10.0}));
  EXPECT_EQ(g.placement().origin_m, Vec3(1, 2, 3));
  // Voxel 0, 0.55 µm: σa = 1·0.5 + 2·0.25, σs = 1·2 + 2·1, g = (2·0.6 + 2·(−0.3)) / 4.
  EXPECT_FLOAT_EQ(g.sigma_a(0)[0], 1.0f);
  EXPECT_FLOAT_EQ(g.sigma_s(0)[0], 4.0f);
  EXPECT_FLOAT_EQ(g.g(0)[0], 0.15f);
  // 10 µm: only B scatters, so g is B's exactly.
  EXPECT_FLOAT_EQ(g.sigma_a(1)[0], 0.7f);
  EXPECT_FLOAT_EQ(g.sigma_s(1)[0], 1.0f);
  EXPECT_EQ(g.g(1)[0], 0.2f);
  // Voxel 1 is clear: no coefficients; g is the k_sca-weighted mean of the
  // species' g, (2·0.6 + 1·(−0.3)) / 3 = 0.3 at 0.55 µm, B's 0.2 at 10 µm.
  EXPECT_EQ(g.sigma_a(0)[1], 0.0f);
  EXPECT_EQ(g.sigma_s(0)[1], 0.0f);
  EXPECT_EQ(g.sigma_s(1)[1], 0.0f);
  EXPECT_FLOAT_EQ(g.g(0)[1], 0.3f);
  EXPECT_FLOAT_EQ(g.g(1)[1], 0.2f);
  // Voxel 2 holds A alone: its g bit for bit where it scatters.
  EXPECT_FLOAT_EQ(g.sigma_a(0)[2], 1.5f);
  EXPECT_FLOAT_EQ(g.sigma_s(0)[2], 6.0f);
  EXPECT_EQ(g.g(0)[2], 0.6f);
  EXPECT_FLOAT_EQ(g.sigma_a(1)[2], 0.3f);
  EXPECT_EQ(g.sigma_s(1)[2], 0.0f);
  // The temperature is the cloud's.
  EXPECT_EQ(g.temperature()[0], 300.0f);
  EXPECT_EQ(g.temperature()[1], 288.0f);
  EXPECT_EQ(g.temperature()[2], 350.0f);
}

TEST(ExpandSpecies, OneSpeciesIsConcentrationTimesMassCoefficients) {
  SpeciesCloud c;
  c.dims = {4, 3, 2};
  c.wavelengths_um = {4.0};
  c.species = {{"smoke", {4.0}, {0.123456789}, {0.987654321}, {0.7}}};
  c.concentration_g_m3.resize(1);
  for (std::size_t v = 0; v < c.dims.count(); ++v) {
    c.concentration_g_m3[0].push_back(0.37f * static_cast<float>(v));
    c.temperature_k.push_back(280.0f + static_cast<float>(v));
  }
  const VoxelGrid g = expand_species(c, "test");
  for (std::size_t v = 0; v < c.dims.count(); ++v) {
    const double conc = c.concentration_g_m3[0][v];
    EXPECT_EQ(g.sigma_a(0)[v], static_cast<float>(conc * 0.123456789)) << v;
    EXPECT_EQ(g.sigma_s(0)[v], static_cast<float>(conc * 0.987654321)) << v;
    EXPECT_EQ(g.g(0)[v], 0.7f) << v;  // clear voxel 0 included
    EXPECT_EQ(g.temperature()[v], c.temperature_k[v]) << v;
  }
  EXPECT_EQ(c.memory_bytes(), 2 * c.dims.count() * sizeof(float));
}

// Expects `fn` to throw InputError whose message contains every one of `parts`.
void expect_error(const std::function<void()>& fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

TEST(ExpandSpecies, BadInputNamesTheSpeciesAndField) {
  SpeciesCloud c = two_species();
  c.species[1].wavelengths_um = {0.55, 10.5};
  expect_error([&] { expand_species(c, "cloud.vdb"); },
               {"cloud.vdb", "species/1/wavelengths_um", "'B'", "10.5"});
  c = two_species();
  c.species[0].mass_scattering_m2_g[1] = -1;
  expect_error([&] { expand_species(c, "x"); }, {"species/0/mass_scattering_m2_g/1", "'A'"});
  c = two_species();
  c.species[1].asymmetry[0] = 1.0;
  expect_error([&] { expand_species(c, "x"); }, {"species/1/asymmetry/0", "'B'"});
  c = two_species();
  c.species[0].asymmetry.pop_back();
  expect_error([&] { expand_species(c, "x"); }, {"species/0/asymmetry", "'A'"});
  c = two_species();
  c.concentration_g_m3[1][2] = -0.5f;
  expect_error([&] { expand_species(c, "x"); }, {"concentration_001 voxel (2,0,0)", "-0.5"});
  c = two_species();
  c.concentration_g_m3[0][1] = std::numeric_limits<float>::infinity();
  expect_error([&] { expand_species(c, "x"); }, {"concentration_000 voxel (1,0,0)"});
  c = two_species();
  c.temperature_k[0] = -1.0f;
  expect_error([&] { expand_species(c, "x"); }, {"temperature voxel (0,0,0)"});
  c = two_species();
  c.concentration_g_m3.pop_back();
  expect_error([&] { expand_species(c, "x"); }, {"concentration", "2 species"});
  c = two_species();
  c.temperature_k.pop_back();
  expect_error([&] { expand_species(c, "x"); }, {"temperature"});
  c = two_species();
  c.species.clear();
  c.concentration_g_m3.clear();
  expect_error([&] { expand_species(c, "x"); }, {"species"});
  c = two_species();
  c.species[0].name.clear();
  expect_error([&] { expand_species(c, "x"); }, {"species/0/name"});
  // A product beyond the float range is caught by the grid's own check.
  c = two_species();
  c.species[0].mass_absorption_m2_g[0] = 1e300;
  expect_error([&] { expand_species(c, "x"); }, {"sigma_a_000 voxel (0,0,0)"});
}

}  // namespace
}  // namespace obscura
