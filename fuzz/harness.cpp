#include "harness.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"

namespace obscura::fuzz {
namespace {

std::vector<Harness>& registry() {
  static std::vector<Harness> r;
  return r;
}

void remove_scratch();

const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    // /dev/shm where it exists and is writable, else the temporary folder.
    const std::string name = "obscura-fuzz-" + std::to_string(::getpid());
    std::error_code ec;
    std::filesystem::path d = std::filesystem::path("/dev/shm") / name;
    if (!std::filesystem::create_directories(d, ec) || ec) {
      d = std::filesystem::temp_directory_path() / name;
      std::filesystem::create_directories(d);
    }
    return d;
  }();
  return dir;
}

void remove_scratch() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir(), ec);
}

}  // namespace

void prepare_process() { set_memory_limit(kFuzzMemoryLimitBytes, MemoryLimitSource::kCommandLine); }

bool register_harness(const char* name, HarnessFunction run) {
  auto& r = registry();
  r.push_back({name, run});
  std::sort(r.begin(), r.end(),
            [](const Harness& a, const Harness& b) { return std::string_view(a.name) < b.name; });
  return true;
}

const std::vector<Harness>& harnesses() { return registry(); }

const Harness* find_harness(std::string_view name) {
  for (const Harness& h : registry())
    if (name == h.name) return &h;
  return nullptr;
}

std::filesystem::path scratch_file(std::string_view name, std::string_view bytes) {
  const std::filesystem::path path = scratch_dir() / std::string(name);
  // Registered after the folder's path is constructed, so that it runs before
  // the path is destroyed at exit. (libFuzzer ends some runs with _Exit, which
  // skips it: `make fuzz` may leave a folder under /dev/shm.)
  [[maybe_unused]] static const bool removed_at_exit = std::atexit(remove_scratch) == 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write the scratch file %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void run_harness(const Harness& harness, std::string_view bytes) {
  try {
    harness.run(bytes);
  } catch (const obscura::InternalError& e) {
    std::fprintf(stderr, "fuzz %s: internal error: %s\n", harness.name, e.what());
    std::abort();
  } catch (const obscura::Error&) {
    // The outcome a bad input should have: a message naming file and field.
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "fuzz %s: not an obscura::Error (the tool would say 'internal error'): %s\n",
                 harness.name, e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz %s: an exception of unknown type\n", harness.name);
    std::abort();
  }
}

void ignore_input_errors(const std::function<void()>& read) {
  try {
    read();
  } catch (const obscura::InternalError&) {
    throw;  // a bug: run_harness reports it
  } catch (const obscura::Error&) {
  }
}

}  // namespace obscura::fuzz
