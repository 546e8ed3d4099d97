#pragma once
// The keyword level of the VTK STRUCTURED_POINTS reader
// (io/vtk_structured_points.h): the header, the geometry keywords, the
// POINT_DATA / CELL_DATA sections and their attribute and FIELD arrays, and
// the frame made of the selected arrays. Internal to io/.
#include <cstdint>
#include <filesystem>
#include <string>

#include "obscura/io/vtk_data_arrays.h"
#include "obscura/io/vtk_grid_geometry.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/io/vtk_token_reader.h"

namespace obscura::vtk_legacy {

class DatasetParser {
 public:
  DatasetParser(const std::filesystem::path& path, const VtkArrayNames& names)
      : tokens_(path), names_(names), geometry_(tokens_), arrays_(tokens_, names, geometry_) {}

  // Parses the whole file; the frame is at `time_s`.
  ConcentrationFrame run(double time_s);

 private:
  void read_header();
  void read_body();
  [[noreturn]] void fail_unexpected(const Token& t) const;
  void begin_section(const Token& kw, Section s);
  bool read_attribute(const Token& t, const std::string& kw);
  void read_scalars(const Token& t);
  void read_field();
  ArrayDecl declare(const Token& t, const std::string& keyword);
  ConcentrationFrame make_frame(double time_s);

  TokenReader tokens_;
  const VtkArrayNames& names_;
  GridGeometry geometry_;
  ArrayReader arrays_;
  Section section_ = Section::kNone;
  std::uint64_t section_count_ = 0;
};

}  // namespace obscura::vtk_legacy
