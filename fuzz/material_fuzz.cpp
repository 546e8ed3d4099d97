// A material file (data/materials/*.json, docs/materials.md): refractive
// indices, size distributions, tabulated mass coefficients.
#include "harness.h"
#include "obscura/optics/material.h"

OBSCURA_FUZZ_HARNESS(material) {
  const auto path = obscura::fuzz::scratch_file("material.json", bytes);
  obscura::fuzz::expect_clean("material", [&] { obscura::load_material(path); });
}
