// `validate slab` against published and converged discrete-ordinates values:
// total reflectance R and transmittance T of a laterally infinite slab with
// Henyey–Greenstein scattering, lit by a collimated beam or diffuse light,
// computed by the path tracer through reciprocity (docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/validation/validation_cases.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

const std::string kTable = std::string(OBSCURA_SOURCE_DIR) + "/data/validation/slab_reference.csv";

// Monte Carlo agreement for a test of `k` comparisons: within the tolerance, or
// within z standard errors where z keeps the whole test's false-failure rate at
// 0.1 % (Šidák: two-sided normal quantile of 1e-3/k; 3.29 for one comparison).
double z_for(int k) {
  // Bisection on erfc(z/√2) = 1e-3/k.
  double lo = 0, hi = 10;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > 1e-3 / k ? lo : hi) = mid;
  }
  return hi;
}

::testing::AssertionResult agrees(const ValidationRow& r, double reference, double z,
                                  double tolerance = 0.01) {
  const double diff = std::abs(r.obtained - reference);
  if (diff <= std::max(z * r.stderr_mean, tolerance * reference) &&
      r.stderr_mean <= tolerance * reference)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << r.case_name << " " << r.quantity << ": obtained " << r.obtained << " ± "
         << r.stderr_mean << ", reference " << reference << " (relative error "
         << (r.obtained - reference) / reference << ")";
}

const ValidationRow& quantity(const std::vector<ValidationRow>& rows, const std::string& q) {
  for (const auto& r : rows)
    if (r.quantity == q) return r;
  throw std::runtime_error("no row " + q);
}

// Van de Hulst (1980), Multiple Light Scattering, vol. 1 Table 12 (isotropic
// scattering) and vol. 2 Table 37 (HG, g = 0.75), as the published DISORT test
// problems 1a–1d, 3a and 3b (Stamnes et al., DISOTEST; stored answers, about
// 1e-3 relative). Values from the rows of data/validation/slab_reference.csv
// whose source is "published test suite". Problems 1e and 1f (τ = 32,
// albedo ≥ 0.99) are left to docs/validation.md: the backward estimator needs
// minutes for them (1e's transmittance is not resolved in 5e7 paths).
struct Published {
  const char* problem;
  SlabSpec slab;
};

std::optional<SlabReference> published_row(const SlabSpec& s) {
  std::ifstream in(kTable);
  std::string line;
  std::getline(in, line);
  const std::string incidence = s.incidence == SlabIncidence::kDiffuse
                                    ? "diffuse_isotropic"
                                    : (s.mu0 == 1.0 ? "collimated_normal" : "collimated_mu0=0.1");
  while (std::getline(in, line)) {
    if (line.find("published test suite") == std::string::npos) continue;
    std::stringstream ss(line);
    std::string f[7];
    for (auto& x : f) std::getline(ss, x, ',');
    if (std::stod(f[0]) == s.albedo && std::stod(f[1]) == s.tau && std::stod(f[2]) == s.g &&
        f[3] == incidence)
      return SlabReference{std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), "published"};
  }
  return std::nullopt;
}

// The path tracer (the reference solver) at 1 %, and the radiance cache at
// 2 % (its photons and lattice periodic across the slab's sides, issue 13).
// The cache's camera rays are sampled until their standard error is half
// the case's 1 % (so z·stderr stays within the 2 % for z ≤ 4), in batches
// of 10 000 rather than the default 50 000: most quantities get there
// within 20 000 rays, and marching the rays is most of these tests' time.
ValidationOptions for_method(RenderMethod method) {
  ValidationOptions o;
  o.settings.method = method;
  o.settings.radiance_cache.photons_per_node = 1000000;
  if (method == RenderMethod::kRadianceCache) o.batch_samples = 10000;
  return o;
}

void published_problems(RenderMethod method, double tolerance) {
  const Published all[] = {
      {"1a", {0.2, 0.03125, 0.0, SlabIncidence::kCollimated, 0.1}},
      {"1b", {1.0, 0.03125, 0.0, SlabIncidence::kCollimated, 0.1}},
      {"1c", {0.99, 0.03125, 0.0, SlabIncidence::kDiffuse, 1.0}},
      {"1d", {0.2, 32.0, 0.0, SlabIncidence::kCollimated, 0.1}},
      {"3a", {1.0, 1.0, 0.75, SlabIncidence::kCollimated, 1.0}},
      {"3b", {1.0, 8.0, 0.75, SlabIncidence::kCollimated, 1.0}},
  };
  const double z = z_for(12);
  for (const auto& p : all) {
    // The radiance cache's hardest is 1d (docs/validation.md): at τ 32 a
    // cell of the default lattice is one optical depth thick and the grazing
    // sun's (μ0 0.1) depth climbs by 10 across it. The march integrates the
    // sun's light over pieces of such cells (R read +24 % with one parabola
    // per cell; −0.22 % now).
    const double within = tolerance;
    const auto ref = published_row(p.slab);
    ASSERT_TRUE(ref) << "problem " << p.problem << " missing from " << kTable;
    const auto rows = validate_slab(p.slab, ref, for_method(method));
    EXPECT_TRUE(agrees(quantity(rows, "R"), ref->r, z, within)) << "problem " << p.problem;
    if (ref->t > 0)
      EXPECT_TRUE(agrees(quantity(rows, "T"), ref->t, z, within)) << "problem " << p.problem;
    else
      EXPECT_LT(quantity(rows, "T").obtained, 1e-6) << "problem " << p.problem;
  }
}

TEST(SlabValidation, VanDeHulstPublishedProblems) {
  published_problems(RenderMethod::kPathTracer, 0.01);
}

TEST(SlabValidation, RadianceCacheVanDeHulstPublishedProblems) {
  published_problems(RenderMethod::kRadianceCache, 0.02);
}

// Every (albedo, τ, g, incidence) of the converged DISORT grid (NSTR = 128,
// ~1e-9): albedo {0.5, 0.9, 0.99} × τ {0.1, 1, 4} × g {0, 0.5, 0.85}; `gs`
// the asymmetries tested.
void converged_grid(RenderMethod method, double tolerance, const std::vector<double>& gs,
                    int expected) {
  const double z = z_for(expected);
  int compared = 0;
  for (double albedo : {0.5, 0.9, 0.99})
    for (double tau : {0.1, 1.0, 4.0})
      for (double g : gs)
        for (auto incidence : {SlabIncidence::kCollimated, SlabIncidence::kDiffuse}) {
          const SlabSpec slab{albedo, tau, g, incidence, 1.0};
          const auto ref = find_slab_reference(kTable, slab);
          ASSERT_TRUE(ref);
          ASSERT_EQ(ref->source.rfind("computed: DISORT", 0), 0u) << ref->source;
          const auto rows = validate_slab(slab, ref, for_method(method));
          EXPECT_TRUE(agrees(quantity(rows, "R"), ref->r, z, tolerance));
          EXPECT_TRUE(agrees(quantity(rows, "T"), ref->t, z, tolerance));
          EXPECT_TRUE(agrees(quantity(rows, "T_direct"), ref->t_direct, z, tolerance));
          compared += 3;
        }
  EXPECT_EQ(compared, expected);
}

TEST(SlabValidation, ConvergedDisortGrid) {
  converged_grid(RenderMethod::kPathTracer, 0.01, {0.0, 0.5, 0.85}, 162);
}

// The radiance cache on the rows with g ≤ 0.5, at its defaults (degree 2).
TEST(SlabValidation, RadianceCacheConvergedDisortGrid) {
  converged_grid(RenderMethod::kRadianceCache, 0.02, {0.0, 0.5}, 108);
}

// The rows with g = 0.85, at spherical-harmonic degree 6 with delta-M
// (cache_source.h; docs/validation.md), every one to the issue's 2 %.
// Measured: R within 1.5 %, T within 0.5 %. At degree 3 the three thin
// slabs (τ 0.1) under the diffuse sky read R −4.5 to −5.7 % (delta-M's
// truncation of the sky's light scattered once across the horizon: −5.6 %
// in a one-dimensional model of the same estimate, docs/validation.md), at
// degree 2 down to −9.1 %; before delta-M −7 to +35 %. These bounds catch
// all of them.
TEST(SlabValidation, RadianceCacheDisortGridWithAPeakedPhaseFunction) {
  constexpr int kRows = 18;
  const double z = z_for(3 * kRows);
  ValidationOptions o = for_method(RenderMethod::kRadianceCache);
  o.settings.radiance_cache.sh_degree = 6;
  int compared = 0;
  for (double albedo : {0.5, 0.9, 0.99})
    for (double tau : {0.1, 1.0, 4.0})
      for (auto incidence : {SlabIncidence::kCollimated, SlabIncidence::kDiffuse}) {
        const SlabSpec slab{albedo, tau, 0.85, incidence, 1.0};
        const auto ref = find_slab_reference(kTable, slab);
        ASSERT_TRUE(ref);
        ASSERT_EQ(ref->source.rfind("computed: DISORT", 0), 0u) << ref->source;
        const auto rows = validate_slab(slab, ref, o);
        EXPECT_TRUE(agrees(quantity(rows, "R"), ref->r, z, 0.02));
        EXPECT_TRUE(agrees(quantity(rows, "T"), ref->t, z, 0.02));
        EXPECT_TRUE(agrees(quantity(rows, "T_direct"), ref->t_direct, z, 0.02));
        ++compared;
      }
  EXPECT_EQ(compared, kRows);
}

// `obscura validate slab` judges the radiance cache on the tables at its 2 %
// target, as the photon map, and the path tracer at the case's 1 %.
TEST(SlabValidation, TheRadianceCacheIsJudgedOnTheTablesAtTwoPercent) {
  const SlabSpec slab{0.9, 1.0, 0.5, SlabIncidence::kCollimated, 1.0};
  const auto ref = find_slab_reference(kTable, slab);
  ASSERT_TRUE(ref);
  ValidationOptions cache = for_method(RenderMethod::kRadianceCache);
  cache.settings.radiance_cache.photons_per_node = 20000;
  cache.samples = 20000;
  ValidationOptions path = for_method(RenderMethod::kPathTracer);
  path.samples = 20000;
  for (const char* q : {"R", "T"}) {
    EXPECT_EQ(quantity(validate_slab(slab, ref, cache), q).tolerance, 0.02) << q;
    EXPECT_EQ(quantity(validate_slab(slab, ref, path), q).tolerance, 0.01) << q;
  }
}

TEST(SlabValidation, UnscatteredTransmittanceHasItsClosedForm) {
  // T_direct is judged against e^{−τ/μ0} or 2 E3(τ) even with no table row.
  const auto normal =
      validate_slab({0.7, 0.37, 0.2, SlabIncidence::kCollimated, 0.6}, std::nullopt, {});
  EXPECT_NEAR(quantity(normal, "T_direct").reference, std::exp(-0.37 / 0.6), 1e-15);
  EXPECT_TRUE(quantity(normal, "T_direct").pass);
  EXPECT_FALSE(quantity(normal, "R").judged);
  const auto diffuse =
      validate_slab({0.7, 1.0, 0.2, SlabIncidence::kDiffuse, 1.0}, std::nullopt, {});
  // 2 E3(1) = 0.219383934 (the table's analytic T_unscattered; A&S Table 5.1).
  EXPECT_NEAR(quantity(diffuse, "T_direct").reference, 0.219383934, 1e-9);
  EXPECT_TRUE(quantity(diffuse, "T_direct").pass);
}

TEST(SlabValidation, ANarrowSlabLosesLightThroughItsEdges) {
  // The default half-width (1e6 thicknesses) is laterally infinite for these
  // cases; a slab as wide as it is thick loses a measurable share of R and T.
  const SlabSpec wide{0.99, 4.0, 0.0, SlabIncidence::kCollimated, 1.0};
  SlabSpec narrow = wide;
  narrow.half_width_m = 0.5;
  ValidationOptions o;
  o.samples = 200000;
  const auto w = validate_slab(wide, std::nullopt, o), n = validate_slab(narrow, std::nullopt, o);
  const double lost = (quantity(w, "R").obtained + quantity(w, "T").obtained) -
                      (quantity(n, "R").obtained + quantity(n, "T").obtained);
  EXPECT_GT(lost, 0.1);
  // The conservative-limit check: R + T of the wide slab is 1 − absorbed, and
  // with albedo 0.99 and τ = 4 the DISORT reference gives R + T = 0.9205.
  EXPECT_NEAR(quantity(w, "R").obtained + quantity(w, "T").obtained, 0.645046554 + 0.275480136,
              0.01);
}

TEST(SlabValidation, ResultsDoNotDependOnTheThreadCount) {
  const SlabSpec slab{0.9, 1.0, 0.5, SlabIncidence::kDiffuse, 1.0};
  ValidationOptions one, two;
  one.samples = two.samples = 20000;
  one.settings.seed = two.settings.seed = 7;
  one.settings.threads = 1;
  two.settings.threads = 2;
  const auto a = validate_slab(slab, std::nullopt, one), b = validate_slab(slab, std::nullopt, two);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].obtained, b[i].obtained) << a[i].quantity;
    EXPECT_EQ(a[i].stderr_mean, b[i].stderr_mean) << a[i].quantity;
  }
}

// Sampled to the target (samples 0), each quantity stops at the first whole
// batch whose standard error is below half the tolerance: with batches of
// 10 000, some stop where batches of 50 000 could not (here R stops at 90 000 paths, T at 10 000).
TEST(SlabValidation, SamplingToTheTargetStopsAtAWholeBatch) {
  const SlabSpec slab{0.9, 1.0, 0.5, SlabIncidence::kCollimated, 1.0};
  const auto ref = find_slab_reference(kTable, slab);
  ASSERT_TRUE(ref);
  ValidationOptions o;
  o.batch_samples = 10000;
  bool finer = false;
  for (const auto& r : validate_slab(slab, ref, o)) {
    EXPECT_EQ(r.samples % 10000, 0) << r.quantity;
    EXPECT_LE(r.stderr_mean, 0.5 * 0.01 * std::abs(r.reference)) << r.quantity;
    if (r.quantity != "T_direct") finer = finer || r.samples % 50000 != 0;  // T_direct is exact
  }
  EXPECT_TRUE(finer);
  o.batch_samples = 999;
  try {
    validate_slab(slab, ref, o);
    ADD_FAILURE() << "a batch of 999 draws was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "batch_samples");
  }
}

class SlabReferenceTable : public testing::TempDirTest {};

TEST_F(SlabReferenceTable, FindsTheConvergedRowAndReportsBadTables) {
  const auto r = find_slab_reference(kTable, {0.9, 1.0, 0.5, SlabIncidence::kCollimated, 1.0});
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->r, 0.129793276);
  EXPECT_DOUBLE_EQ(r->t, 0.739091109);
  EXPECT_FALSE(find_slab_reference(kTable, {0.3, 1.0, 0.5, SlabIncidence::kCollimated, 1.0}));

  const auto bad = dir_ / "bad.csv";
  std::ofstream(bad) << "albedo,tau,g,incidence,R_total,T_total,T_unscattered,source\n"
                     << "0.9,1.0,0.5,collimated_normal,0.1,oops,0.3,x\n";
  try {
    find_slab_reference(bad.string(), {0.9, 1.0, 0.5, SlabIncidence::kCollimated, 1.0});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "line 2");
    EXPECT_NE(std::string(e.what()).find("oops"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_slab_reference((dir_ / "missing.csv").string(), {}), InputError);
}

}  // namespace
}  // namespace obscura
