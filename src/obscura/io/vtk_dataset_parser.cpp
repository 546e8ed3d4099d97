#include "obscura/io/vtk_dataset_parser.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

#include "obscura/core/error.h"

namespace obscura::vtk_legacy {
namespace {

std::string lower_to_upper(const std::string& s) {
  std::string out = s;
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Every concentration finite and ≥ 0 after scaling to g/m³.
void scale_and_check_concentration(ScalarGrid& c, const VtkArrayNames& names,
                                   const std::string& file) {
  const double scale = names.concentration_to_g_m3;
  for (int k = 0; k < c.dims.nz; ++k)
    for (int j = 0; j < c.dims.ny; ++j)
      for (int i = 0; i < c.dims.nx; ++i) {
        float& v = c.values[c.index(i, j, k)];
        if (scale != 1.0) v = static_cast<float>(v * scale);
        if (!std::isfinite(v) || v < 0.0f)
          throw InputError(file, fmt::format("{} voxel ({},{},{})", names.concentration, i, j, k),
                           fmt::format("concentration {} g/m³ is {}", v,
                                       std::isfinite(v) ? "negative" : "not finite"));
      }
}

// Every temperature finite and > 0 K.
void check_temperature(const ScalarGrid& t, const VtkArrayNames& names, const std::string& file) {
  for (int k = 0; k < t.dims.nz; ++k)
    for (int j = 0; j < t.dims.ny; ++j)
      for (int i = 0; i < t.dims.nx; ++i) {
        const float v = t.at(i, j, k);
        if (!(std::isfinite(v) && v > 0.0f))
          throw InputError(file, fmt::format("{} voxel ({},{},{})", names.temperature, i, j, k),
                           fmt::format("temperature {} K must be finite and > 0", v));
      }
}

}  // namespace

ConcentrationFrame DatasetParser::run(double time_s) {
  read_header();
  read_body();
  return make_frame(time_s);
}

// "# vtk DataFile Version x.y", a title line, ASCII | BINARY,
// DATASET STRUCTURED_POINTS (VTK File Formats, "Simple Legacy Formats").
void DatasetParser::read_header() {
  Lexer& lex = tokens_.lexer();
  const auto first = lex.read_line();
  static constexpr std::string_view kMagic = "# vtk DataFile Version";
  if (!first || first->rfind(kMagic, 0) != 0)
    throw InputError(
        lex.file(), "line 1",
        fmt::format("not a VTK legacy file: the first line must start with '{}'", kMagic));
  if (!lex.read_line()) throw InputError(lex.file(), "line 2", "file ends before the title line");
  const Token enc = tokens_.expect_token("ASCII or BINARY");
  const std::string e = lower(enc.text);
  if (e == "ascii")
    tokens_.set_binary(false);
  else if (e == "binary")
    tokens_.set_binary(true);
  else
    tokens_.fail(enc, fmt::format("expected ASCII or BINARY, found '{}'", enc.text));
  const Token ds = tokens_.expect_token("DATASET");
  if (lower(ds.text) != "dataset")
    tokens_.fail(ds, fmt::format("expected DATASET STRUCTURED_POINTS, found '{}'", ds.text));
  const Token type = tokens_.expect_token("the dataset type");
  if (lower(type.text) != "structured_points")
    tokens_.fail(type,
                 fmt::format("DATASET {} is not supported: obscura imports only STRUCTURED_POINTS "
                             "(a regular grid); resample the data onto one first",
                             type.text));
}

void DatasetParser::read_body() {
  Token t;
  while (tokens_.lexer().next(t)) {
    const std::string kw = lower(t.text);
    if ((kw == "dimensions" || kw == "origin" || kw == "spacing" || kw == "aspect_ratio") &&
        section_ != Section::kNone) {
      tokens_.fail(
          t, fmt::format("{} after POINT_DATA / CELL_DATA: the geometry must come first", t.text));
    } else if (kw == "dimensions") {
      geometry_.read_dimensions(t);
    } else if (kw == "origin") {
      geometry_.read_origin();
    } else if (kw == "spacing" || kw == "aspect_ratio") {  // ASPECT_RATIO: pre-VTK-4 name
      geometry_.read_spacing(t);
    } else if (kw == "point_data" || kw == "cell_data") {
      begin_section(t, kw == "point_data" ? Section::kPoints : Section::kCells);
    } else if (kw == "field") {
      read_field();
    } else if (kw == "metadata") {
      tokens_.skip_metadata();
    } else if (section_ != Section::kNone && read_attribute(t, kw)) {
      // an attribute of the current POINT_DATA / CELL_DATA section
    } else {
      fail_unexpected(t);
    }
  }
}

// A token that is no keyword here: a stray value (a count too small), or an
// unknown keyword.
void DatasetParser::fail_unexpected(const Token& t) const {
  if (parse_ascii_value(ValueType{"double", ValueKind::kDouble, 8}, t.text))
    tokens_.fail(t, arrays_.last_array().empty()
                        ? fmt::format("found the value '{}' where a keyword was expected", t.text)
                        : fmt::format("found the value '{}' where a keyword was expected: {} has "
                                      "more values than declared (DIMENSIONS or the {} count "
                                      "wrong?)",
                                      t.text, arrays_.last_array(), section_keyword(section_)));
  tokens_.fail(t, fmt::format("unexpected keyword '{}' (expected {})", t.text,
                              section_ == Section::kNone
                                  ? "DIMENSIONS, ORIGIN, SPACING, FIELD, POINT_DATA or CELL_DATA"
                                  : "SCALARS, FIELD, VECTORS, NORMALS, TENSORS, "
                                    "TEXTURE_COORDINATES, COLOR_SCALARS, LOOKUP_TABLE, "
                                    "POINT_DATA or CELL_DATA"));
}

void DatasetParser::begin_section(const Token& kw, Section s) {
  section_count_ = geometry_.read_section_count(kw, s);
  section_ = s;
}

// One dataset attribute of POINT_DATA / CELL_DATA (VTK File Formats,
// "Dataset Attribute Format"). Returns false for an unknown keyword.
bool DatasetParser::read_attribute(const Token& t, const std::string& kw) {
  const std::uint64_t n = section_count_;
  if (kw == "scalars") {
    read_scalars(t);
  } else if (kw == "color_scalars") {
    ArrayDecl a = declare(t, "COLOR_SCALARS");
    a.components = tokens_.expect_integer<std::uint64_t>("the COLOR_SCALARS component count", 1, 4);
    // Binary color scalars are unsigned chars, ASCII ones floats in [0, 1].
    a.type = tokens_.binary() ? *parse_value_type("unsigned_char") : *parse_value_type("float");
    a.tuples = n;
    arrays_.take(a);
  } else if (kw == "lookup_table") {
    ArrayDecl a = declare(t, "LOOKUP_TABLE");
    a.tuples = tokens_.expect_integer<std::uint64_t>("the LOOKUP_TABLE size", 0,
                                                     std::numeric_limits<std::int64_t>::max());
    a.components = 4;  // RGBA
    a.type = tokens_.binary() ? *parse_value_type("unsigned_char") : *parse_value_type("float");
    a.section = Section::kNone;  // not data on the grid: never selected
    arrays_.skip(a);
  } else if (kw == "vectors" || kw == "normals" || kw == "tensors" || kw == "tensors6" ||
             kw == "global_ids" || kw == "pedigree_ids" || kw == "edge_flags") {
    ArrayDecl a = declare(t, lower_to_upper(kw));
    a.type = tokens_.expect_type();
    a.tuples = n;
    a.components = (kw == "vectors" || kw == "normals") ? 3
                   : kw == "tensors"                    ? 9
                   : kw == "tensors6"                   ? 6
                                                        : 1;
    arrays_.take(a);
  } else if (kw == "texture_coordinates") {
    ArrayDecl a = declare(t, "TEXTURE_COORDINATES");
    a.components = tokens_.expect_integer<std::uint64_t>("the TEXTURE_COORDINATES dimension", 1, 3);
    a.type = tokens_.expect_type();
    a.tuples = n;
    arrays_.take(a);
  } else {
    return false;
  }
  return true;
}

// SCALARS name type [numComp] LOOKUP_TABLE tableName: the component count is
// optional, so the token after the type is either it or LOOKUP_TABLE
// (vtkDataReader::ReadScalarData).
void DatasetParser::read_scalars(const Token& t) {
  ArrayDecl a = declare(t, "SCALARS");
  a.type = tokens_.expect_type();
  a.tuples = section_count_;
  const auto bad_lookup = [&](const Token& at) {
    tokens_.fail(at, fmt::format("'SCALARS {} {}' must be followed by an optional component count "
                                 "(1 to 4) and 'LOOKUP_TABLE <name>' (e.g. LOOKUP_TABLE default), "
                                 "found '{}'",
                                 a.name, a.type.name, at.text));
  };
  Token next = tokens_.expect_token("LOOKUP_TABLE");
  if (lower(next.text) != "lookup_table") {
    int nc = 0;
    const auto [ptr, ec] =
        std::from_chars(next.text.data(), next.text.data() + next.text.size(), nc);
    if (ec != std::errc() || ptr != next.text.data() + next.text.size() || nc < 1 || nc > 4)
      bad_lookup(next);
    a.components = static_cast<std::uint64_t>(nc);
    next = tokens_.expect_token("LOOKUP_TABLE");
  }
  if (lower(next.text) != "lookup_table") bad_lookup(next);
  tokens_.expect_token("the lookup table name");
  arrays_.take(a);
}

ArrayDecl DatasetParser::declare(const Token& t, const std::string& keyword) {
  ArrayDecl a;
  a.keyword = keyword;
  a.at = t;
  a.section = section_;
  a.name = decode_name(tokens_.expect_token(fmt::format("the {} name", keyword)).text);
  return a;
}

// FIELD name numArrays, then per array "name numComponents numTuples type"
// and its values (VTK File Formats, "Field Data"; a VTK ≥ 5 writer may put
// a METADATA block after each array). Inside POINT_DATA / CELL_DATA these
// arrays are grid data like SCALARS (ParaView writes all but the active
// scalars this way); at dataset level (e.g. a TIME value) they are skipped.
void DatasetParser::read_field() {
  tokens_.expect_token("the FIELD name");
  const int count = tokens_.expect_integer<int>("the FIELD array count", 0, 1 << 20);
  for (int i = 0; i < count; ++i) {
    Token name = tokens_.expect_token("a FIELD array name");
    if (lower(name.text) == "metadata") {
      tokens_.skip_metadata();
      name = tokens_.expect_token("a FIELD array name");
    }
    if (name.text == "NULL_ARRAY") continue;  // an empty slot, no data (vtkDataReader)
    ArrayDecl a;
    a.keyword = "FIELD";
    a.at = name;
    a.name = decode_name(name.text);
    a.section = section_;
    a.components = tokens_.expect_integer<std::uint64_t>(
        fmt::format("the component count of FIELD array '{}'", a.name), 1, 1 << 20);
    a.tuples = tokens_.expect_integer<std::uint64_t>(
        fmt::format("the tuple count of FIELD array '{}'", a.name), 0,
        std::numeric_limits<std::int64_t>::max());
    const Token type_token = tokens_.expect_token("a data type");
    if (lower(type_token.text) == "string" || lower(type_token.text) == "utf8_string" ||
        lower(type_token.text) == "variant")
      tokens_.fail(type_token,
                   fmt::format("FIELD array '{}' has type {}, which obscura cannot read or "
                               "skip; remove it from the file",
                               a.name, type_token.text));
    tokens_.lexer().push_back(type_token);
    a.type = tokens_.expect_type();
    if (section_ != Section::kNone && arrays_.is_selected(a.name) && a.tuples != section_count_)
      tokens_.fail(name, fmt::format("FIELD array '{}' has {} tuples but {} declares {}", a.name,
                                     a.tuples, section_keyword(section_), section_count_));
    arrays_.take(a);
  }
}

ConcentrationFrame DatasetParser::make_frame(double time_s) {
  const std::string& file = tokens_.file();
  if (!geometry_.dims()) tokens_.fail_at_end("the file has no DIMENSIONS");
  std::optional<SelectedArray>& conc = arrays_.concentration();
  std::optional<SelectedArray>& temp = arrays_.temperature();
  if (!conc)
    throw InputError(
        file, names_.concentration,
        fmt::format("no array named '{}'; {}", names_.concentration, arrays_.list_found()));
  if (!names_.temperature.empty() && !temp)
    throw InputError(
        file, names_.temperature,
        fmt::format("no array named '{}'; {}", names_.temperature, arrays_.list_found()));
  if (temp && temp->section != conc->section)
    tokens_.fail(temp->at,
                 fmt::format("temperature array '{}' is {} but concentration array '{}' is {}: "
                             "both must be on the same grid",
                             names_.temperature, section_keyword(temp->section),
                             names_.concentration, section_keyword(conc->section)));
  ConcentrationFrame frame;
  frame.time_s = time_s;
  frame.concentration_g_m3 =
      geometry_.make_grid(conc->section, conc->at, std::move(conc->values), "concentration");
  conc.reset();
  scale_and_check_concentration(frame.concentration_g_m3, names_, file);
  if (temp) {
    frame.temperature_k =
        geometry_.make_grid(temp->section, temp->at, std::move(temp->values), "temperature");
    temp.reset();
    check_temperature(*frame.temperature_k, names_, file);
  }
  return frame;
}

}  // namespace obscura::vtk_legacy
