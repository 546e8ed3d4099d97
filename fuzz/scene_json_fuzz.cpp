// The scene JSON (docs/formats.md), with the tables it holds: sky zenith
// tables, the sun's irradiance table, band responses, surface emissivities.
// Files it names are looked for beside it, in the scratch folder.
#include "harness.h"
#include "obscura/scene/scene.h"

OBSCURA_FUZZ_HARNESS(scene_json) {
  obscura::load_scene(obscura::fuzz::scratch_file("scene.json", bytes));
}
