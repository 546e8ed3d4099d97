// libFuzzer's entry points for one harness, named at compile time by
// OBSCURA_FUZZ_HARNESS_NAME (fuzz/CMakeLists.txt builds one fuzzer per name).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "harness.h"

namespace {
const obscura::fuzz::Harness* harness = nullptr;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  obscura::fuzz::prepare_process();
  harness = obscura::fuzz::find_harness(OBSCURA_FUZZ_HARNESS_NAME);
  if (!harness) {
    std::fprintf(stderr, "fuzz: no harness named %s is linked in\n", OBSCURA_FUZZ_HARNESS_NAME);
    std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  obscura::fuzz::run_harness(*harness, {reinterpret_cast<const char*>(data), size});
  return 0;
}
