// A terrain heightfield (CSV of heights in m).
#include "harness.h"
#include "obscura/scene/heightfield.h"

OBSCURA_FUZZ_HARNESS(heightfield_csv) {
  const auto path = obscura::fuzz::scratch_file("terrain.csv", bytes);
  obscura::fuzz::expect_clean("heightfield_csv", [&] { obscura::read_heightfield_csv(path); });
}
