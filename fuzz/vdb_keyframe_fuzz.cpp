// A cloud keyframe (OpenVDB), in both forms the reader accepts: spectral
// (σa, σs, g per wavelength and temperature) and species (concentrations and
// their optics table). One reader serves both; the two harnesses differ in
// their seed corpora, so that each form's structure gets mutated.
#include "harness.h"
#include "obscura/io/vdb_keyframe.h"

namespace {
void read_keyframe(const char* harness, std::string_view bytes) {
  const auto path = obscura::fuzz::scratch_file("keyframe.vdb", bytes);
  obscura::fuzz::expect_clean(harness, [&] { obscura::read_cloud_keyframe(path); });
}
}  // namespace

OBSCURA_FUZZ_HARNESS(vdb_spectral_keyframe) { read_keyframe("vdb_spectral_keyframe", bytes); }
OBSCURA_FUZZ_HARNESS(vdb_species_keyframe) { read_keyframe("vdb_species_keyframe", bytes); }
