// A cloud keyframe (OpenVDB), in both forms the reader accepts: spectral
// (σa, σs, g per wavelength and temperature) and species (concentrations and
// their optics table). One reader serves both; the two harnesses differ in
// their seed corpora, so that each form's structure gets mutated.
#include "harness.h"
#include "obscura/io/vdb_keyframe.h"

namespace {
void read_keyframe(std::string_view bytes) {
  obscura::read_cloud_keyframe(obscura::fuzz::scratch_file("keyframe.vdb", bytes));
}
}  // namespace

OBSCURA_FUZZ_HARNESS(vdb_spectral_keyframe) { read_keyframe(bytes); }
OBSCURA_FUZZ_HARNESS(vdb_species_keyframe) { read_keyframe(bytes); }
