// A material file (data/materials/*.json, docs/materials.md): refractive
// indices, size distributions, tabulated mass coefficients.
#include "harness.h"
#include "obscura/optics/material.h"

OBSCURA_FUZZ_HARNESS(material) {
  obscura::load_material(obscura::fuzz::scratch_file("material.json", bytes));
}
