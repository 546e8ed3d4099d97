#pragma once
// Random streams. Every pixel (and later every photon) owns its own pcg32
// stream, selected by its index, so a result never depends on which thread
// ran which pixel or in what order (O'Neill 2014, PCG: stream selection).
#include <cstdint>
#include <pcg_random.hpp>

namespace obscura {

class Rng {
 public:
  // `seed` is the user's seed; `stream` identifies the consumer (pixel index, photon index).
  Rng(std::uint64_t seed, std::uint64_t stream) : engine_(seed, stream) {}

  // Uniform double in [0, 1) with 32 random bits (enough for sampling; exact multiples of 2^-32).
  double uniform() { return static_cast<double>(engine_()) * 0x1p-32; }
  std::uint32_t next_u32() { return engine_(); }

 private:
  pcg32 engine_;
};

}  // namespace obscura
