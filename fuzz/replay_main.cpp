// Runs saved inputs through a harness without libFuzzer, with any compiler:
// the test suite replays every seed corpus and every regression input this
// way (fuzz/CMakeLists.txt), so a fixed crash stays fixed in the ordinary
// build. A finding aborts, which fails the test.
//
//   obscura_fuzz_replay HARNESS PATH...   files, or folders of files (one input each)
//   obscura_fuzz_replay --list            the harnesses linked in
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "harness.h"

namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int usage() {
  std::fprintf(stderr, "usage: obscura_fuzz_replay HARNESS PATH... | --list\n");
  return 64;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::string(argv[1]) == "--list") {
    for (const auto& h : obscura::fuzz::harnesses()) std::printf("%s\n", h.name);
    return 0;
  }
  if (argc < 3) return usage();
  const obscura::fuzz::Harness* harness = obscura::fuzz::find_harness(argv[1]);
  if (!harness) {
    std::fprintf(stderr, "obscura_fuzz_replay: no harness named '%s' (see --list)\n", argv[1]);
    return 64;
  }
  std::vector<fs::path> inputs;
  for (int i = 2; i < argc; ++i) {
    const fs::path p = argv[i];
    if (fs::is_directory(p)) {
      for (const auto& e : fs::directory_iterator(p))
        if (e.is_regular_file()) inputs.push_back(e.path());
    } else if (fs::is_regular_file(p)) {
      inputs.push_back(p);
    } else {
      std::fprintf(stderr, "obscura_fuzz_replay: %s: no such file or folder\n", p.c_str());
      return 66;
    }
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "obscura_fuzz_replay: no inputs under the paths given\n");
    return 66;
  }
  std::sort(inputs.begin(), inputs.end());
  obscura::fuzz::prepare_process();
  for (const fs::path& p : inputs) {
    std::fprintf(stderr, "%s: %s\n", harness->name, p.c_str());
    obscura::fuzz::run_harness(*harness, read_bytes(p));
  }
  std::printf("%s: %zu inputs read without a finding\n", harness->name, inputs.size());
  return 0;
}
