// An animated cloud's manifest (cloud.json: keyframes, lifecycle, trajectory).
#include "harness.h"
#include "obscura/io/cloud_manifest.h"

OBSCURA_FUZZ_HARNESS(cloud_manifest) {
  obscura::read_cloud_manifest(obscura::fuzz::scratch_file("cloud.json", bytes));
}
