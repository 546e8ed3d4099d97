#include "obscura/io/provenance.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "obscura/core/error.h"
#include "obscura/core/version.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

TEST(Sha256, KnownVectors) {
  // FIPS 180-2 appendix B.1 and the empty message.
  EXPECT_EQ(sha256_bytes("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_bytes(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, FileMatchesBytes) {
  const fs::path p = fs::path(::testing::TempDir()) / "obscura_sha256_file.bin";
  // Larger than the read buffer, so the incremental path is exercised.
  std::string content(200000, '\0');
  for (size_t i = 0; i < content.size(); ++i) content[i] = static_cast<char>(i * 7 + 3);
  {
    std::ofstream out(p, std::ios::binary);
    out << content;
  }
  EXPECT_EQ(sha256_file(p), sha256_bytes(content));
  fs::remove(p);
}

TEST(Sha256, UnreadableFileThrowsInputError) {
  const fs::path p = fs::path(::testing::TempDir()) / "obscura_no_such_file.vdb";
  try {
    sha256_file(p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p.string());
    EXPECT_NE(std::string(e.what()).find("cannot read file"), std::string::npos);
  }
}

TEST(JoinCommandLine, QuotesOnlyWhatTheShellWouldSplit) {
  const char* argv[] = {"obscura", "render", "--out=dir/a.exr", "my scene.json", "it's", ""};
  EXPECT_EQ(join_command_line(6, argv),
            "obscura render --out=dir/a.exr 'my scene.json' 'it'\\''s' ''");
  const char* dollar[] = {"a$b", "x*"};
  EXPECT_EQ(join_command_line(2, dollar), "'a$b' 'x*'");
}

TEST(Provenance, JsonRoundTrip) {
  Provenance p;
  p.version = "1.2.3";
  p.command_line = "obscura render 'a b.json'";
  p.seed = 18446744073709551615ull;  // full uint64 range survives JSON
  p.inputs = {{"a b.json", sha256_bytes("x")}, {"cloud.vdb", sha256_bytes("y")}};
  p.created_utc = "2024-05-01T12:34:56Z";
  const std::string text = p.to_string();
  EXPECT_EQ(text.find('\n'), std::string::npos);  // compact
  const Provenance q = Provenance::from_json(nlohmann::json::parse(text));
  EXPECT_EQ(q.software, "obscura");
  EXPECT_EQ(q.version, p.version);
  EXPECT_EQ(q.command_line, p.command_line);
  EXPECT_EQ(q.seed, p.seed);
  ASSERT_EQ(q.inputs.size(), 2u);
  EXPECT_EQ(q.inputs[1].path, "cloud.vdb");
  EXPECT_EQ(q.inputs[1].sha256, sha256_bytes("y"));
  EXPECT_EQ(q.created_utc, p.created_utc);
}

TEST(Provenance, FromJsonRejectsMissingKey) {
  nlohmann::json j = Provenance{}.to_json();
  j.erase("seed");
  EXPECT_THROW(Provenance::from_json(j), Error);
}

TEST(Provenance, MakeFillsVersionHashesAndTime) {
  const fs::path p = fs::path(::testing::TempDir()) / "obscura_prov_input.json";
  {
    std::ofstream out(p, std::ios::binary);
    out << "abc";
  }
  const Provenance prov = make_provenance("obscura render x", 42, {p});
  EXPECT_EQ(prov.version, kVersion);
  EXPECT_EQ(prov.seed, 42u);
  ASSERT_EQ(prov.inputs.size(), 1u);
  EXPECT_EQ(prov.inputs[0].path, p.string());
  EXPECT_EQ(prov.inputs[0].sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_TRUE(
      std::regex_match(prov.created_utc, std::regex(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z)")))
      << prov.created_utc;
  fs::remove(p);
  EXPECT_THROW(make_provenance("x", 0, {p}), InputError);
}

}  // namespace
}  // namespace obscura
