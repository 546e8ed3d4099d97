#pragma once
// How much memory obscura may take, checked before any size read from a file
// or scene is allocated (a grid, an image, a photon map, a mesh): a corrupt or
// hostile header gets a message saying what it would need, not std::bad_alloc
// or the OOM killer taking a shared machine's other work down with it.
//
// The limit is process-wide: by default a fraction of the memory the machine
// has available when first asked, else what a scene's "max_memory" or the
// command line's --max-memory set (the command line wins over the scene).
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace obscura {

// The default limit as a fraction of the available memory.
inline constexpr double kDefaultMemoryFraction = 0.75;

// Physical memory currently available (bytes): /proc/meminfo MemAvailable, or
// sysconf where that is missing.
std::uint64_t available_memory_bytes();

// Who set the limit; a later setting replaces an earlier one only when it
// comes from the same or a stronger source.
enum class MemoryLimitSource { kDefault, kScene, kCommandLine };

void set_memory_limit(std::uint64_t bytes, MemoryLimitSource source);
// Back to the default (for tests).
void reset_memory_limit();

// The current limit in bytes.
std::uint64_t memory_limit_bytes();

// "3.2 GiB of memory is available (75% of what the machine has free; …)":
// the tail of every refusal, saying where the limit comes from.
std::string memory_limit_text();

// Throws InputError(file, field, "<what> needs N GiB but only <memory_limit_text>")
// when `bytes` exceeds the limit.
void check_memory(std::uint64_t bytes, const std::string& file, const std::string& field,
                  std::string_view what);

// "4GiB", "500MB", "1.5G", "2048" (bytes): binary units (KiB, MiB, GiB, TiB,
// and K, M, G, T) are powers of 1024, decimal ones (kB, MB, GB, TB) of 1000.
// Empty when the text is not such a size or is zero.
std::optional<std::uint64_t> parse_memory_size(std::string_view text);

// The product of the factors, or empty when it overflows 64 bits.
std::optional<std::uint64_t> checked_product(std::initializer_list<std::uint64_t> factors);

}  // namespace obscura
