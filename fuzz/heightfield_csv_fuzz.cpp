// A terrain heightfield (CSV of heights in m).
#include "harness.h"
#include "obscura/scene/heightfield.h"

OBSCURA_FUZZ_HARNESS(heightfield_csv) {
  obscura::read_heightfield_csv(obscura::fuzz::scratch_file("terrain.csv", bytes));
}
