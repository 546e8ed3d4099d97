#include "obscura/core/memory_limit.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>

#include "obscura/core/error.h"

namespace obscura {
namespace {

struct Limit {
  std::mutex mutex;
  bool set = false;
  std::uint64_t bytes = 0;
  MemoryLimitSource source = MemoryLimitSource::kDefault;
};

Limit& limit() {
  static Limit l;
  return l;
}

// The default, computed once: MemAvailable moves as other processes run, and
// one run should check every size against the same limit.
std::uint64_t default_limit() {
  static const std::uint64_t bytes = static_cast<std::uint64_t>(
      static_cast<double>(available_memory_bytes()) * kDefaultMemoryFraction);
  return bytes;
}

double gib(std::uint64_t bytes) { return static_cast<double>(bytes) / 1073741824.0; }

}  // namespace

std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t value = 0;
  std::string unit;
  while (meminfo >> key >> value >> unit) {
    if (key == "MemAvailable:") return value * 1024;
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page_size > 0)
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
  return std::numeric_limits<std::uint64_t>::max();
}

void set_memory_limit(std::uint64_t bytes, MemoryLimitSource source) {
  Limit& l = limit();
  std::lock_guard lock(l.mutex);
  if (l.set && source < l.source) return;
  l.set = true;
  l.bytes = bytes;
  l.source = source;
}

void reset_memory_limit() {
  Limit& l = limit();
  std::lock_guard lock(l.mutex);
  l.set = false;
  l.source = MemoryLimitSource::kDefault;
}

std::uint64_t memory_limit_bytes() {
  Limit& l = limit();
  std::lock_guard lock(l.mutex);
  return l.set ? l.bytes : default_limit();
}

std::string memory_limit_text() {
  Limit& l = limit();
  MemoryLimitSource source;
  std::uint64_t bytes;
  {
    std::lock_guard lock(l.mutex);
    source = l.set ? l.source : MemoryLimitSource::kDefault;
    bytes = l.set ? l.bytes : default_limit();
  }
  switch (source) {
    case MemoryLimitSource::kCommandLine:
      return fmt::format("{:.3g} GiB of memory is available (the limit set by --max-memory)",
                         gib(bytes));
    case MemoryLimitSource::kScene:
      return fmt::format("{:.3g} GiB of memory is available (the scene's max_memory)", gib(bytes));
    case MemoryLimitSource::kDefault:
      break;
  }
  return fmt::format(
      "{:.3g} GiB of memory is available ({:.0f}% of what the machine has free; --max-memory "
      "changes it)",
      gib(bytes), 100 * kDefaultMemoryFraction);
}

void check_memory(std::uint64_t bytes, const std::string& file, const std::string& field,
                  std::string_view what) {
  if (bytes <= memory_limit_bytes()) return;
  throw InputError(
      file, field,
      fmt::format("{} needs {:.3g} GiB but only {}", what, gib(bytes), memory_limit_text()));
}

std::optional<std::uint64_t> parse_memory_size(std::string_view text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || !std::isfinite(value) || value <= 0) return std::nullopt;
  std::string unit(ptr, end);
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  struct Unit {
    const char* name;
    double factor;
  };
  static const Unit units[] = {
      {"", 1},
      {"b", 1},
      {"k", 1024.0},
      {"kib", 1024.0},
      {"m", 1048576.0},
      {"mib", 1048576.0},
      {"g", 1073741824.0},
      {"gib", 1073741824.0},
      {"t", 1099511627776.0},
      {"tib", 1099511627776.0},
      {"kb", 1e3},
      {"mb", 1e6},
      {"gb", 1e9},
      {"tb", 1e12},
  };
  for (const Unit& u : units) {
    if (unit != u.name) continue;
    const double bytes = value * u.factor;
    if (!(bytes >= 1) || bytes >= 1.8e19) return std::nullopt;
    return static_cast<std::uint64_t>(bytes);
  }
  return std::nullopt;
}

std::optional<std::uint64_t> checked_product(std::initializer_list<std::uint64_t> factors) {
  std::uint64_t p = 1;
  for (const std::uint64_t f : factors)
    if (__builtin_mul_overflow(p, f, &p)) return std::nullopt;
  return p;
}

}  // namespace obscura
