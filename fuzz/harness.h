#pragma once
// One fuzz harness per parser (docs/reliability.md). A harness hands the
// fuzzer's bytes to a parser the way the tool does (as a file) and accepts two
// outcomes only: the input is read, or the parser throws obscura::Error, the
// clear message the tool prints with exit code 1. Anything else is a finding:
// another exception (the tool's "internal error", exit 2), a crash, a
// sanitizer report or a leak. run_harness judges the outcome.
//
// The same harness files build two ways: with clang's libFuzzer, one fuzzer
// per harness (the `fuzz` preset, `make fuzz`); and with any compiler, one
// replay tool that runs the checked-in corpora and regression inputs through
// every harness in the ordinary test suite (fuzz/CMakeLists.txt).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace obscura::fuzz {

using HarnessFunction = void (*)(std::string_view bytes);

struct Harness {
  const char* name;
  HarnessFunction run;
};

// What a harness's parser may allocate (core/memory_limit.h): an input that
// claims more is refused by the checks under test, well inside libFuzzer's
// 2 GB RSS limit. Small, so that the fuzzer spends its time on parsing and
// not on zero-filling the large grids a mutated size may still ask for (at
// 256 MiB the VDB harnesses fell from ~700 to ~25 executions per second);
// every seed needs less than 4 MiB.
inline constexpr std::uint64_t kFuzzMemoryLimitBytes = 32ull << 20;

// Sets the memory limit; called once before the first input.
void prepare_process();

// Called once per harness at static initialisation (OBSCURA_FUZZ_HARNESS).
bool register_harness(const char* name, HarnessFunction run);
// Every harness linked into this program, sorted by name.
const std::vector<Harness>& harnesses();
const Harness* find_harness(std::string_view name);

// Writes `bytes` to the file `name` in this process's scratch folder (under
// /dev/shm where it exists, so that millions of executions do not wear a
// disk) and returns its path. The folder is removed when the process exits.
std::filesystem::path scratch_file(std::string_view name, std::string_view bytes);

// Runs one input through `harness` and judges the outcome: returns when the
// parser read it or threw obscura::Error; reports anything else (another
// exception, an InternalError) with the harness's name and aborts, which
// libFuzzer records as a crash and the replay tool as a failed test. Both
// drivers call this; a harness itself just calls its parser.
void run_harness(const Harness& harness, std::string_view bytes);

// For a harness that reads one input twice (with other options): runs `read`
// and swallows obscura::Error only, so that the second read still runs and
// anything else still reaches run_harness.
void ignore_input_errors(const std::function<void()>& read);

}  // namespace obscura::fuzz

// Defines and registers a harness: OBSCURA_FUZZ_HARNESS(obj_mesh) { ... bytes ... }
#define OBSCURA_FUZZ_HARNESS(name)                                    \
  static void obscura_fuzz_##name(std::string_view bytes);            \
  [[maybe_unused]] static const bool obscura_fuzz_registered_##name = \
      ::obscura::fuzz::register_harness(#name, obscura_fuzz_##name);  \
  static void obscura_fuzz_##name(std::string_view bytes)
