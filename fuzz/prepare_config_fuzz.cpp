// A `prepare` configuration, read and checked in full (prep/prepare_config.h)
// without running the dispersion model or reading the CFD files it names.
#include "harness.h"
#include "obscura/io/json_reader.h"
#include "obscura/prep/prepare_config.h"

OBSCURA_FUZZ_HARNESS(prepare_config) {
  const auto path = obscura::fuzz::scratch_file("prepare.json", bytes);
  obscura::read_prepare_config(obscura::read_json_file(path.string()), path);
}
