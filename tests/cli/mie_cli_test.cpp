// `obscura mie`: a reference value, the JSON keys, radius and wavelength in
// place of the size parameter, and bad input (exit status 1, the option named).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>

#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class MieCliTest : public testing::TempDirTest {
 protected:
  testing::CliResult run(const std::string& args) { return testing::run_cli("mie " + args, dir_); }
};

// The row x = 10, m = 1.5 + 0.01i of mie_reference.csv (miepython, confirmed
// by MIEV0): Qext 2.7706950638, Qsca 2.3441316270, g 0.79372319509.
TEST_F(MieCliTest, ReferenceValueAsJson) {
  const auto r = run("--size-parameter 10 --index 1.5,0.01 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["qext"].get<double>(), 2.7706950638, 1e-9);
  EXPECT_NEAR(j["qsca"].get<double>(), 2.3441316270, 1e-9);
  EXPECT_NEAR(j["g"].get<double>(), 0.79372319509, 1e-9);
  EXPECT_NEAR(j["qabs"].get<double>(), j["qext"].get<double>() - j["qsca"].get<double>(), 1e-12);
  EXPECT_GT(j["qback"].get<double>(), 0.0);
}

TEST_F(MieCliTest, JsonKeys) {
  const auto r = run("--size-parameter 10 --index 1.5,0.01 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::set<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  EXPECT_EQ(keys, (std::set<std::string>{"size_parameter", "index", "qext", "qsca", "qabs", "qback",
                                         "g"}));
  EXPECT_EQ(j["size_parameter"].get<double>(), 10.0);
  EXPECT_EQ(j["index"]["real"].get<double>(), 1.5);
  EXPECT_EQ(j["index"]["imag"].get<double>(), 0.01);
}

// Bohren & Huffman's BHMIE example (app. A): r = 0.525 µm, λ = 0.6328 µm,
// m = 1.55: Qext = Qsca = 3.10543, Qback = 2.92534. The index without an
// imaginary part is non-absorbing.
TEST_F(MieCliTest, RadiusAndWavelength) {
  const auto r = run("--radius-um 0.525 --wavelength-um 0.6328 --index 1.55 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["size_parameter"].get<double>(), 2 * std::numbers::pi * 0.525 / 0.6328, 1e-12);
  EXPECT_NEAR(j["qext"].get<double>(), 3.10543, 5e-6);
  EXPECT_NEAR(j["qback"].get<double>(), 2.92534, 5e-6);
  EXPECT_EQ(j["qabs"].get<double>(), 0.0);
  EXPECT_EQ(j["radius_um"].get<double>(), 0.525);
  EXPECT_EQ(j["wavelength_um"].get<double>(), 0.6328);
}

TEST_F(MieCliTest, TextOutput) {
  const auto r = run("--size-parameter 10 --index 1.5,0.01");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s :
       {"Qext   2.770695064", "Qsca   2.344131627", "Qabs", "Qback", "g      0.7937231951"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
}

TEST_F(MieCliTest, BadInputNamesTheOption) {
  const struct {
    const char* args;
    const char* option;
  } cases[] = {
      {"--size-parameter 0 --index 1.5,0", "--size-parameter"},
      {"--size-parameter abc --index 1.5,0", "--size-parameter"},
      {"--size-parameter 1e7 --index 1.5,0", "--size-parameter"},
      {"--size-parameter 10 --index 1.5,-0.1", "--index"},
      {"--size-parameter 10 --index 0,1", "--index"},
      {"--size-parameter 10 --index x", "--index"},
      {"--size-parameter 10", "--index"},
      {"--index 1.5,0", "--size-parameter"},
      {"--size-parameter 10 --radius-um 1 --wavelength-um 1 --index 1.5,0", "--size-parameter"},
      {"--radius-um 1 --index 1.5,0", "--wavelength-um"},
      {"--wavelength-um 1 --index 1.5,0", "--radius-um"},
      {"--radius-um -1 --wavelength-um 1 --index 1.5,0", "--radius-um"},
      {"--radius-um 1 --wavelength-um 0 --index 1.5,0", "--wavelength-um"},
  };
  for (const auto& c : cases) {
    const auto r = run(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(std::string("obscura: error: ") + c.option), std::string::npos)
        << c.args << "\n"
        << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args << "\n" << r.out;
  }
}

}  // namespace
}  // namespace obscura
