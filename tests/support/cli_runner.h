#pragma once
// Runs the `obscura` binary built beside the tests, capturing its exit status,
// stdout and stderr (through files in a scratch folder). OBSCURA_TEST_CLI, when
// set, names another binary to run instead: CI runs the bad-input catalogue
// against the sanitizer build's tool (scripts/ci-sanitizers, docs/testing.md).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace obscura::testing {

struct CliResult {
  int status = -1;
  std::string out, err;
};

inline std::string read_text_file(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The tool under test: OBSCURA_TEST_CLI if set, else the one built beside the tests.
inline std::string cli_path() {
  const char* other = std::getenv("OBSCURA_TEST_CLI");
  return other != nullptr && *other != '\0' ? std::string(other) : std::string(OBSCURA_CLI_PATH);
}

// `args` is appended to the binary's path as given (shell syntax).
inline CliResult run_cli(const std::string& args, const std::filesystem::path& scratch) {
  const auto out = scratch / "cli_stdout.txt", err = scratch / "cli_stderr.txt";
  const std::string cmd = cli_path() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_text_file(out), read_text_file(err)};
}

}  // namespace obscura::testing
