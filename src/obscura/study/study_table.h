#pragma once
// The results of a parameter study as one table (docs/studies.md): one row
// per case with its parameters (each axis's label), its status and error,
// and per sensor and band the time to screen (s), the screening duration (s),
// the lowest mean transmittance over the target (1) and the largest screened
// fraction (1). Written as results.csv, results.json and results.nc (NetCDF-
// CF: dimension case, one variable per column, units and long names, NaN
// where a case failed or was never screened), and the screening duration of
// every case as a plot (screening.png), each atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "obscura/io/provenance.h"
#include "obscura/study/study_runner.h"

namespace obscura {

// The (sensor, band) columns of the table: every pair any case measured, in
// order of first appearance.
std::vector<std::pair<std::string, std::string>> study_series_columns(const StudyResult& result);

// The CSV text of the table (RFC 4180 quoting; empty cells where a case
// failed or was never screened).
std::string study_results_csv(const StudySpec& spec, const StudyResult& result);

// Writes the table's files into `out_dir`; returns their paths.
std::vector<std::filesystem::path> write_study_results(const StudySpec& spec,
                                                       const StudyResult& result,
                                                       const std::filesystem::path& out_dir,
                                                       const Provenance& provenance);

}  // namespace obscura
