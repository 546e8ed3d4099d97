#include "obscura/io/vtk_structured_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/vtk_legacy_lexer.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {
namespace {

using vtk_legacy::binary_value;
using vtk_legacy::decode_name;
using vtk_legacy::encode_name;
using vtk_legacy::Lexer;
using vtk_legacy::lower;
using vtk_legacy::parse_ascii_value;
using vtk_legacy::parse_value_type;
using vtk_legacy::Token;
using vtk_legacy::ValueKind;
using vtk_legacy::ValueType;

// Cubic voxels: spacings that differ by more than this (relative) are refused.
constexpr double kIsotropyTolerance = 1e-6;
// Frames of a series share a grid when origins agree to this fraction of a voxel.
constexpr double kSameGridTolerance = 1e-9;

// ---------------------------------------------------------------------------
enum class Section { kNone, kPoints, kCells };

const char* section_keyword(Section s) {
  return s == Section::kPoints  ? "POINT_DATA"
         : s == Section::kCells ? "CELL_DATA"
                                : "dataset FIELD";
}

// One array as declared in the file: what is read or skipped, and what the
// "array not found" message lists.
struct ArrayDecl {
  std::string keyword;  // SCALARS, FIELD, VECTORS, ...
  std::string name;
  ValueType type;
  std::uint64_t components = 1;
  std::uint64_t tuples = 0;
  Section section = Section::kNone;
  Token at;  // the keyword (or FIELD array name) token
  std::string describe() const {
    return fmt::format("{} '{}' ({}, {} x {} {})", keyword, name, section_keyword(section), tuples,
                       components, type.name);
  }
};

struct SelectedArray {
  std::vector<float> values;
  Section section = Section::kNone;
  Token at;
};

class VtkParser {
 public:
  VtkParser(const std::filesystem::path& path, const VtkArrayNames& names)
      : lex_(path, path.string()), names_(names) {}

  ConcentrationFrame run(double time_s) {
    read_header();
    read_body();
    return make_frame(time_s);
  }

 private:
  [[noreturn]] void fail(const Token& t, const std::string& what) const {
    throw InputError(lex_.file(), Lexer::where(t), what);
  }
  [[noreturn]] void fail_here(const std::string& what) const {
    throw InputError(lex_.file(), lex_.where(), what);
  }
  [[noreturn]] void fail_at_end(const std::string& what) const {
    throw InputError(lex_.file(), lex_.where_end(), what);
  }

  Token expect_token(const std::string& what) {
    Token t;
    if (!lex_.next(t)) fail_at_end(fmt::format("file ends where {} was expected", what));
    return t;
  }
  template <typename T>
  T expect_integer(const std::string& what, T min_value, T max_value) {
    const Token t = expect_token(what);
    long long v = 0;
    auto [ptr, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec != std::errc() || ptr != t.text.data() + t.text.size())
      fail(t, fmt::format("expected {} (an integer), found '{}'", what, t.text));
    if (v < static_cast<long long>(min_value) ||
        static_cast<unsigned long long>(v) > static_cast<unsigned long long>(max_value))
      fail(t, fmt::format("{} {} is outside [{}, {}]", what, v, min_value, max_value));
    return static_cast<T>(v);
  }
  double expect_double(const std::string& what) {
    const Token t = expect_token(what);
    const auto v = parse_ascii_value(ValueType{"double", ValueKind::kDouble, 8}, t.text);
    if (!v) fail(t, fmt::format("expected {} (a number), found '{}'", what, t.text));
    if (!std::isfinite(*v)) fail(t, fmt::format("{} is {}, not a finite number", what, t.text));
    return *v;
  }

  // "# vtk DataFile Version x.y", a title line, ASCII | BINARY,
  // DATASET STRUCTURED_POINTS (VTK File Formats, "Simple Legacy Formats").
  void read_header() {
    const auto first = lex_.read_line();
    static constexpr std::string_view kMagic = "# vtk DataFile Version";
    if (!first || first->rfind(kMagic, 0) != 0)
      throw InputError(
          lex_.file(), "line 1",
          fmt::format("not a VTK legacy file: the first line must start with '{}'", kMagic));
    if (!lex_.read_line())
      throw InputError(lex_.file(), "line 2", "file ends before the title line");
    const Token enc = expect_token("ASCII or BINARY");
    const std::string e = lower(enc.text);
    if (e == "ascii")
      binary_ = false;
    else if (e == "binary")
      binary_ = true;
    else
      fail(enc, fmt::format("expected ASCII or BINARY, found '{}'", enc.text));
    const Token ds = expect_token("DATASET");
    if (lower(ds.text) != "dataset")
      fail(ds, fmt::format("expected DATASET STRUCTURED_POINTS, found '{}'", ds.text));
    const Token type = expect_token("the dataset type");
    if (lower(type.text) != "structured_points")
      fail(type, fmt::format("DATASET {} is not supported: obscura imports only STRUCTURED_POINTS "
                             "(a regular grid); resample the data onto one first",
                             type.text));
  }

  void read_body() {
    Token t;
    while (lex_.next(t)) {
      const std::string kw = lower(t.text);
      if ((kw == "dimensions" || kw == "origin" || kw == "spacing" || kw == "aspect_ratio") &&
          section_ != Section::kNone) {
        fail(t,
             fmt::format("{} after POINT_DATA / CELL_DATA: the geometry must come first", t.text));
      } else if (kw == "dimensions") {
        read_dimensions(t);
      } else if (kw == "origin") {
        Vec3 o;
        for (int a = 0; a < 3; ++a) o[a] = expect_double("an ORIGIN component");
        origin_ = o;
      } else if (kw == "spacing" || kw == "aspect_ratio") {  // ASPECT_RATIO: pre-VTK-4 name
        read_spacing(t);
      } else if (kw == "point_data" || kw == "cell_data") {
        begin_section(t, kw == "point_data" ? Section::kPoints : Section::kCells);
      } else if (kw == "field") {
        read_field();
      } else if (kw == "metadata") {
        skip_metadata();
      } else if (section_ != Section::kNone && read_attribute(t, kw)) {
        // an attribute of the current POINT_DATA / CELL_DATA section
      } else if (parse_ascii_value(ValueType{"double", ValueKind::kDouble, 8}, t.text)) {
        fail(t, last_array_.empty()
                    ? fmt::format("found the value '{}' where a keyword was expected", t.text)
                    : fmt::format("found the value '{}' where a keyword was expected: {} has more "
                                  "values than declared (DIMENSIONS or the {} count wrong?)",
                                  t.text, last_array_, section_keyword(section_)));
      } else {
        fail(t, fmt::format("unexpected keyword '{}' (expected {})", t.text,
                            section_ == Section::kNone
                                ? "DIMENSIONS, ORIGIN, SPACING, FIELD, POINT_DATA or CELL_DATA"
                                : "SCALARS, FIELD, VECTORS, NORMALS, TENSORS, "
                                  "TEXTURE_COORDINATES, COLOR_SCALARS, LOOKUP_TABLE, "
                                  "POINT_DATA or CELL_DATA"));
      }
    }
  }

  void read_dimensions(const Token& kw) {
    GridDims d;
    d.nx = expect_integer<int>("DIMENSIONS nx", 1, std::numeric_limits<int>::max());
    d.ny = expect_integer<int>("DIMENSIONS ny", 1, std::numeric_limits<int>::max());
    d.nz = expect_integer<int>("DIMENSIONS nz", 1, std::numeric_limits<int>::max());
    dims_ = d;
    dims_at_ = kw;
  }

  void read_spacing(const Token& kw) {
    Vec3 s;
    for (int a = 0; a < 3; ++a) s[a] = expect_double(fmt::format("{} component", kw.text));
    spacing_ = s;
    spacing_at_ = kw;
  }

  // The voxel size, once DIMENSIONS and SPACING are both known. ScalarGrid
  // voxels are cubes (one voxel_size_m): an anisotropic grid would have to be
  // resampled, which is the CFD post-processor's job. The spacing of an axis
  // with a single point places nothing (writers of 2-D slices put 0 or 1
  // there), so it is ignored; the slice is one voxel thick.
  double voxel_size() const {
    const Vec3& s = *spacing_;
    const int n[3] = {dims_->nx, dims_->ny, dims_->nz};
    const std::string text = fmt::format("{} {} {} {}", spacing_at_.text, s.x, s.y, s.z);
    double h = 0.0;
    for (int a = 0; a < 3; ++a) {
      if (n[a] == 1 && !(n[0] == 1 && n[1] == 1 && n[2] == 1)) continue;
      if (!(s[a] > 0.0)) fail(spacing_at_, text + ": the spacing must be > 0 m");
      if (h == 0.0) {
        h = s[a];
      } else if (std::abs(s[a] - h) > kIsotropyTolerance * h) {
        fail(spacing_at_, fmt::format("{}: obscura grids have cubic voxels, so the spacing must "
                                      "be the same along x, y and z (to a relative {}); resample "
                                      "the data onto an isotropic grid",
                                      text, kIsotropyTolerance));
      }
    }
    return h;
  }

  void begin_section(const Token& kw, Section s) {
    if (!dims_) fail(kw, fmt::format("{} before DIMENSIONS", kw.text));
    if (!spacing_)
      fail(kw, fmt::format("{} before SPACING: the grid spacing is required", kw.text));
    voxel_size_ = voxel_size();
    if (!origin_) fail(kw, fmt::format("{} before ORIGIN: the grid origin is required", kw.text));
    const std::uint64_t n = expect_integer<std::uint64_t>(fmt::format("the {} count", kw.text), 0,
                                                          std::numeric_limits<std::int64_t>::max());
    // Points: nx·ny·nz. Cells: VTK drops axes with a single point
    // (vtkStructuredData), so a 2-D image of 10×10×1 points has 9×9 cells.
    const std::uint64_t expected =
        s == Section::kPoints ? dims_->count()
                              : static_cast<std::uint64_t>(std::max(dims_->nx - 1, 1)) *
                                    static_cast<std::uint64_t>(std::max(dims_->ny - 1, 1)) *
                                    static_cast<std::uint64_t>(std::max(dims_->nz - 1, 1));
    if (n != expected)
      fail(kw, fmt::format("{} {} does not match DIMENSIONS {} {} {} ({}): {} {} expected", kw.text,
                           n, dims_->nx, dims_->ny, dims_->nz, Lexer::where(dims_at_), expected,
                           s == Section::kPoints ? "points" : "cells"));
    section_ = s;
    section_count_ = n;
  }

  // One dataset attribute of POINT_DATA / CELL_DATA (VTK File Formats,
  // "Dataset Attribute Format"). Returns false for an unknown keyword.
  bool read_attribute(const Token& t, const std::string& kw) {
    const std::uint64_t n = section_count_;
    if (kw == "scalars") {
      ArrayDecl a = declare(t, "SCALARS");
      a.type = expect_type();
      a.tuples = n;
      // The next token is either the component count or LOOKUP_TABLE
      // (vtkDataReader::ReadScalarData).
      const auto bad_lookup = [&](const Token& at) {
        fail(at, fmt::format("'SCALARS {} {}' must be followed by an optional component count "
                             "(1 to 4) and 'LOOKUP_TABLE <name>' (e.g. LOOKUP_TABLE default), "
                             "found '{}'",
                             a.name, a.type.name, at.text));
      };
      Token next = expect_token("LOOKUP_TABLE");
      if (lower(next.text) != "lookup_table") {
        int nc = 0;
        const auto [ptr, ec] =
            std::from_chars(next.text.data(), next.text.data() + next.text.size(), nc);
        if (ec != std::errc() || ptr != next.text.data() + next.text.size() || nc < 1 || nc > 4)
          bad_lookup(next);
        a.components = static_cast<std::uint64_t>(nc);
        next = expect_token("LOOKUP_TABLE");
      }
      if (lower(next.text) != "lookup_table") bad_lookup(next);
      expect_token("the lookup table name");
      take_array(a);
    } else if (kw == "color_scalars") {
      ArrayDecl a = declare(t, "COLOR_SCALARS");
      a.components = expect_integer<std::uint64_t>("the COLOR_SCALARS component count", 1, 4);
      // Binary color scalars are unsigned chars, ASCII ones floats in [0, 1].
      a.type = binary_ ? *parse_value_type("unsigned_char") : *parse_value_type("float");
      a.tuples = n;
      take_array(a);
    } else if (kw == "lookup_table") {
      ArrayDecl a = declare(t, "LOOKUP_TABLE");
      a.tuples = expect_integer<std::uint64_t>("the LOOKUP_TABLE size", 0,
                                               std::numeric_limits<std::int64_t>::max());
      a.components = 4;  // RGBA
      a.type = binary_ ? *parse_value_type("unsigned_char") : *parse_value_type("float");
      a.section = Section::kNone;  // not data on the grid: never selected
      skip_values(a);
    } else if (kw == "vectors" || kw == "normals" || kw == "tensors" || kw == "tensors6" ||
               kw == "global_ids" || kw == "pedigree_ids" || kw == "edge_flags") {
      ArrayDecl a = declare(t, lower_to_upper(kw));
      a.type = expect_type();
      a.tuples = n;
      a.components = (kw == "vectors" || kw == "normals") ? 3
                     : kw == "tensors"                    ? 9
                     : kw == "tensors6"                   ? 6
                                                          : 1;
      take_array(a);
    } else if (kw == "texture_coordinates") {
      ArrayDecl a = declare(t, "TEXTURE_COORDINATES");
      a.components = expect_integer<std::uint64_t>("the TEXTURE_COORDINATES dimension", 1, 3);
      a.type = expect_type();
      a.tuples = n;
      take_array(a);
    } else {
      return false;
    }
    return true;
  }

  static std::string lower_to_upper(const std::string& s) {
    std::string out = s;
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
  }

  ArrayDecl declare(const Token& t, const std::string& keyword) {
    ArrayDecl a;
    a.keyword = keyword;
    a.at = t;
    a.section = section_;
    a.name = decode_name(expect_token(fmt::format("the {} name", keyword)).text);
    return a;
  }

  ValueType expect_type() {
    const Token t = expect_token("a data type");
    const auto type = parse_value_type(t.text);
    if (!type)
      fail(t, fmt::format("data type '{}' is not supported (expected float, double, char, "
                          "unsigned_char, short, unsigned_short, int, unsigned_int, long, "
                          "unsigned_long, vtktypeint64, vtktypeuint64, vtkIdType or bit)",
                          t.text));
    return *type;
  }

  // FIELD name numArrays, then per array "name numComponents numTuples type"
  // and its values (VTK File Formats, "Field Data"; a VTK ≥ 5 writer may put
  // a METADATA block after each array). Inside POINT_DATA / CELL_DATA these
  // arrays are grid data like SCALARS (ParaView writes all but the active
  // scalars this way); at dataset level (e.g. a TIME value) they are skipped.
  void read_field() {
    expect_token("the FIELD name");
    const int count = expect_integer<int>("the FIELD array count", 0, 1 << 20);
    for (int i = 0; i < count; ++i) {
      Token name = expect_token("a FIELD array name");
      if (lower(name.text) == "metadata") {
        skip_metadata();
        name = expect_token("a FIELD array name");
      }
      if (name.text == "NULL_ARRAY") continue;  // an empty slot, no data (vtkDataReader)
      ArrayDecl a;
      a.keyword = "FIELD";
      a.at = name;
      a.name = decode_name(name.text);
      a.section = section_;
      a.components = expect_integer<std::uint64_t>(
          fmt::format("the component count of FIELD array '{}'", a.name), 1, 1 << 20);
      a.tuples =
          expect_integer<std::uint64_t>(fmt::format("the tuple count of FIELD array '{}'", a.name),
                                        0, std::numeric_limits<std::int64_t>::max());
      const Token type_token = expect_token("a data type");
      if (lower(type_token.text) == "string" || lower(type_token.text) == "utf8_string" ||
          lower(type_token.text) == "variant")
        fail(type_token, fmt::format("FIELD array '{}' has type {}, which obscura cannot read or "
                                     "skip; remove it from the file",
                                     a.name, type_token.text));
      lex_.push_back(type_token);
      a.type = expect_type();
      if (section_ != Section::kNone && is_selected(a.name) && a.tuples != section_count_)
        fail(name, fmt::format("FIELD array '{}' has {} tuples but {} declares {}", a.name,
                               a.tuples, section_keyword(section_), section_count_));
      take_array(a);
    }
  }

  // METADATA blocks (VTK ≥ 5.1) are text up to the next blank line.
  void skip_metadata() {
    lex_.finish_line();
    while (const auto line = lex_.read_line()) {
      if (line->find_first_not_of(" \t\r") == std::string::npos) break;
    }
  }

  bool is_selected(const std::string& name) const {
    return name == names_.concentration ||
           (!names_.temperature.empty() && name == names_.temperature);
  }

  std::uint64_t value_count(const ArrayDecl& a) const {
    std::uint64_t count = 0;
    if (__builtin_mul_overflow(a.tuples, a.components, &count))
      fail(a.at, fmt::format("{} has {} x {} values, which overflows a 64-bit count", a.describe(),
                             a.tuples, a.components));
    return count;
  }

  // Reads the array if it is the concentration or temperature, skips it otherwise.
  void take_array(const ArrayDecl& a) {
    if (a.section != Section::kNone) found_.push_back(a);
    last_array_ = a.describe();
    if (a.section == Section::kNone || !is_selected(a.name)) {
      skip_values(a);
      return;
    }
    const bool is_conc = a.name == names_.concentration;
    std::optional<SelectedArray>& slot = is_conc ? concentration_ : temperature_;
    if (slot)
      fail(a.at, fmt::format("a second array named '{}' ({} has one already): the choice would "
                             "be ambiguous",
                             a.name, Lexer::where(slot->at)));
    if (a.components != 1)
      fail(a.at, fmt::format("{} has {} components per value; a {} array must have 1", a.describe(),
                             a.components, is_conc ? "concentration" : "temperature"));
    if (a.type.kind == ValueKind::kBit)
      fail(a.at, fmt::format("{} is a bit array; a {} must be numeric", a.describe(),
                             is_conc ? "concentration" : "temperature"));
    const std::uint64_t count = value_count(a);
    // Memory first, before a byte is allocated: a corrupt or hostile header
    // must produce a message, not std::bad_alloc or the OOM killer.
    std::uint64_t bytes = 0, already = 0;
    if (concentration_) already += concentration_->values.size() * sizeof(float);
    if (temperature_) already += temperature_->values.size() * sizeof(float);
    if (__builtin_mul_overflow(count, sizeof(float), &bytes) || bytes > available_memory_bytes())
      fail(a.at, fmt::format("{} on DIMENSIONS {} {} {} needs {:.3g} GiB but only {:.3g} GiB of "
                             "memory is available{}",
                             a.describe(), dims_->nx, dims_->ny, dims_->nz,
                             static_cast<double>(count) * sizeof(float) / 1073741824.0,
                             available_memory_bytes() / 1073741824.0,
                             already > 0
                                 ? fmt::format(" ({:.3g} GiB already read)", already / 1073741824.0)
                                 : std::string()));
    SelectedArray sel;
    sel.section = a.section;
    sel.at = a.at;
    check_available(a, count);
    sel.values.resize(static_cast<std::size_t>(count));
    read_values(a, count, sel.values.data());
    slot = std::move(sel);
  }

  // Before allocating: the bytes the values need must be in the file. Binary
  // values have a fixed size; ASCII ones need at least one character and a
  // separator each.
  void check_available(const ArrayDecl& a, std::uint64_t count) {
    if (binary_) {
      if (count == 0) return;
      lex_.finish_line();
      const std::uint64_t start = lex_.offset();
      const std::uint64_t need = binary_bytes(a, count);
      if (lex_.remaining() < need)
        throw InputError(
            lex_.file(), fmt::format("byte {}", start),
            fmt::format("{}: truncated binary data: {} {} values need {} bytes from byte offset "
                        "{}, but the file ends at byte {} ({} bytes short)",
                        a.describe(), count, a.type.name, need, start, lex_.file_size(),
                        need - lex_.remaining()));
    } else if (count > 0 && count > (lex_.remaining() + 1) / 2) {
      fail(a.at, fmt::format("{}: {} values cannot fit in the {} bytes left in the file (each "
                             "needs a digit and a separator): the file is truncated or {} is "
                             "wrong",
                             a.describe(), count, lex_.remaining(), section_keyword(a.section)));
    }
  }

  std::uint64_t binary_bytes(const ArrayDecl& a, std::uint64_t count) const {
    if (a.type.kind == ValueKind::kBit) return (count + 7) / 8;
    std::uint64_t need = 0;
    if (__builtin_mul_overflow(count, static_cast<std::uint64_t>(a.type.bytes), &need))
      fail(a.at, fmt::format("{}: byte count overflows", a.describe()));
    return need;
  }

  void read_values(const ArrayDecl& a, std::uint64_t count, float* out) {
    if (binary_) {
      // check_available() has consumed the header line and checked the size.
      std::vector<unsigned char> chunk(static_cast<std::size_t>(a.type.bytes) * 65536);
      std::uint64_t done = 0;
      while (done < count) {
        const std::size_t k =
            static_cast<std::size_t>(std::min<std::uint64_t>(65536, count - done));
        const std::size_t nbytes = k * static_cast<std::size_t>(a.type.bytes);
        if (lex_.read(chunk.data(), nbytes) != nbytes)
          fail_here(fmt::format("{}: file ends inside the binary data (after {} of {} values)",
                                a.describe(), done, count));
        for (std::size_t i = 0; i < k; ++i)
          out[done + i] = static_cast<float>(binary_value(a.type, chunk.data() + i * a.type.bytes));
        done += k;
      }
      return;
    }
    Token t;
    for (std::uint64_t i = 0; i < count; ++i) {
      if (!lex_.next(t))
        fail_at_end(
            fmt::format("{}: file ends after {} of {} values: the file is truncated or the "
                        "{} count is wrong",
                        a.describe(), i, count, section_keyword(a.section)));
      const auto v = parse_ascii_value(a.type, t.text);
      if (!v)
        fail(t, fmt::format("{}: '{}' is not a {} value (value {} of {}){}", a.describe(), t.text,
                            a.type.name, i, count,
                            std::isalpha(static_cast<unsigned char>(t.text[0]))
                                ? ": the array has fewer values than declared"
                                : ""));
      if (out != nullptr) out[i] = static_cast<float>(*v);
    }
  }

  void skip_values(const ArrayDecl& a) {
    const std::uint64_t count = value_count(a);
    if (binary_) {
      if (count == 0) return;
      check_available(a, count);  // consumes the header line
      lex_.skip(binary_bytes(a, count));
      return;
    }
    ValueType parse_as = a.type;
    if (parse_as.kind == ValueKind::kBit) parse_as = *parse_value_type("int");
    ArrayDecl as_read = a;
    as_read.type = parse_as;
    read_values(as_read, count, nullptr);
  }

  std::string list_found() const {
    if (found_.empty()) return "the file has no POINT_DATA or CELL_DATA arrays";
    std::string s = "arrays in the file: ";
    for (std::size_t i = 0; i < found_.size(); ++i) s += (i ? ", " : "") + found_[i].describe();
    return s;
  }

  ScalarGrid make_grid(SelectedArray& sel, const std::string& role) const {
    ScalarGrid g;
    const double h = voxel_size_;
    if (sel.section == Section::kPoints) {
      g.dims = *dims_;
      g.placement.origin_m = *origin_ - Vec3(h, h, h) * 0.5;
    } else {
      if (dims_->nx < 2 || dims_->ny < 2 || dims_->nz < 2)
        fail(sel.at, fmt::format("{} is CELL_DATA on DIMENSIONS {} {} {}: a grid with a single "
                                 "point along an axis has flat cells, which are not voxels",
                                 role, dims_->nx, dims_->ny, dims_->nz));
      g.dims = GridDims{dims_->nx - 1, dims_->ny - 1, dims_->nz - 1};
      g.placement.origin_m = *origin_;
    }
    g.placement.voxel_size_m = h;
    g.values = std::move(sel.values);
    return g;
  }

  ConcentrationFrame make_frame(double time_s) {
    if (!dims_) fail_at_end("the file has no DIMENSIONS");
    if (!concentration_)
      throw InputError(lex_.file(), names_.concentration,
                       fmt::format("no array named '{}'; {}", names_.concentration, list_found()));
    if (!names_.temperature.empty() && !temperature_)
      throw InputError(lex_.file(), names_.temperature,
                       fmt::format("no array named '{}'; {}", names_.temperature, list_found()));
    if (temperature_ && temperature_->section != concentration_->section)
      fail(temperature_->at,
           fmt::format("temperature array '{}' is {} but concentration array '{}' is {}: both "
                       "must be on the same grid",
                       names_.temperature, section_keyword(temperature_->section),
                       names_.concentration, section_keyword(concentration_->section)));
    ConcentrationFrame frame;
    frame.time_s = time_s;
    frame.concentration_g_m3 = make_grid(*concentration_, "concentration");
    concentration_.reset();
    ScalarGrid& c = frame.concentration_g_m3;
    const double scale = names_.concentration_to_g_m3;
    for (int k = 0; k < c.dims.nz; ++k)
      for (int j = 0; j < c.dims.ny; ++j)
        for (int i = 0; i < c.dims.nx; ++i) {
          float& v = c.values[c.index(i, j, k)];
          if (scale != 1.0) v = static_cast<float>(v * scale);
          if (!std::isfinite(v) || v < 0.0f)
            throw InputError(lex_.file(),
                             fmt::format("{} voxel ({},{},{})", names_.concentration, i, j, k),
                             fmt::format("concentration {} g/m³ is {}", v,
                                         std::isfinite(v) ? "negative" : "not finite"));
        }
    if (temperature_) {
      frame.temperature_k = make_grid(*temperature_, "temperature");
      temperature_.reset();
      const ScalarGrid& t = *frame.temperature_k;
      for (int k = 0; k < t.dims.nz; ++k)
        for (int j = 0; j < t.dims.ny; ++j)
          for (int i = 0; i < t.dims.nx; ++i) {
            const float v = t.at(i, j, k);
            if (!(std::isfinite(v) && v > 0.0f))
              throw InputError(lex_.file(),
                               fmt::format("{} voxel ({},{},{})", names_.temperature, i, j, k),
                               fmt::format("temperature {} K must be finite and > 0", v));
          }
    }
    return frame;
  }

  Lexer lex_;
  const VtkArrayNames& names_;
  bool binary_ = false;
  std::optional<GridDims> dims_;
  Token dims_at_;
  std::optional<Vec3> origin_;
  std::optional<Vec3> spacing_;
  Token spacing_at_;
  double voxel_size_ = 0.0;
  Section section_ = Section::kNone;
  std::uint64_t section_count_ = 0;
  std::vector<ArrayDecl> found_;
  std::string last_array_;  // for "more values than declared"
  std::optional<SelectedArray> concentration_, temperature_;
};

void check_names(const std::string& file, const VtkArrayNames& names) {
  if (names.concentration.empty())
    throw InputError(file, "concentration", "the concentration array name is empty");
  if (names.temperature == names.concentration)
    throw InputError(
        file, "temperature",
        fmt::format("the temperature array name '{}' is the concentration's", names.temperature));
  if (!(std::isfinite(names.concentration_to_g_m3) && names.concentration_to_g_m3 > 0.0))
    throw InputError(file, "concentration_to_g_m3",
                     fmt::format("scale {} must be finite and > 0", names.concentration_to_g_m3));
}

// ---------------------------------------------------------------------------
// Writer.
class OutFile {
 public:
  explicit OutFile(const std::filesystem::path& path) : path_(path) {
    f_ = std::fopen(path.c_str(), "wb");
    if (f_ == nullptr)
      throw Error(fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  }
  ~OutFile() {
    if (f_ != nullptr) std::fclose(f_);
  }
  OutFile(const OutFile&) = delete;
  OutFile& operator=(const OutFile&) = delete;
  void write(const void* data, std::size_t n) {
    if (std::fwrite(data, 1, n, f_) != n)
      throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }
  void write(std::string_view s) { write(s.data(), s.size()); }
  void close() {
    const int rc = std::fclose(f_);
    f_ = nullptr;
    if (rc != 0)
      throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }

 private:
  std::filesystem::path path_;
  std::FILE* f_ = nullptr;
};

void check_arrays(const std::string& file, const std::vector<VtkScalarArray>& arrays,
                  VtkDataLocation location) {
  if (arrays.empty()) throw InputError(file, "", "nothing to write: no arrays");
  const ScalarGrid* first = arrays.front().grid;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    const VtkScalarArray& a = arrays[i];
    const std::string field = a.name.empty() ? fmt::format("array {}", i) : a.name;
    if (a.name.empty()) throw InputError(file, field, "array name is empty");
    for (std::size_t j = 0; j < i; ++j)
      if (arrays[j].name == a.name) throw InputError(file, field, "two arrays have this name");
    if (a.grid == nullptr) throw InputError(file, field, "no grid");
    const ScalarGrid& g = *a.grid;
    if (g.dims.nx <= 0 || g.dims.ny <= 0 || g.dims.nz <= 0)
      throw InputError(
          file, field,
          fmt::format("dims {}x{}x{} must all be > 0", g.dims.nx, g.dims.ny, g.dims.nz));
    if (g.values.size() != g.dims.count())
      throw InputError(file, field,
                       fmt::format("{} values for a {}x{}x{} grid", g.values.size(), g.dims.nx,
                                   g.dims.ny, g.dims.nz));
    if (!(std::isfinite(g.placement.voxel_size_m) && g.placement.voxel_size_m > 0.0) ||
        !is_finite(g.placement.origin_m))
      throw InputError(file, field, "voxel size must be finite and > 0, origin finite");
    if (!(g.placement.rotation == Mat3::identity()))
      throw InputError(file, field,
                       "a rotated grid cannot be written as VTK STRUCTURED_POINTS (axis-aligned)");
    if (!(g.dims == first->dims) || !(g.placement.origin_m == first->placement.origin_m) ||
        g.placement.voxel_size_m != first->placement.voxel_size_m)
      throw InputError(file, field,
                       fmt::format("grid differs from that of '{}': one dataset has one grid",
                                   arrays.front().name));
    if (location == VtkDataLocation::kCells &&
        std::max({g.dims.nx, g.dims.ny, g.dims.nz}) == std::numeric_limits<int>::max())
      throw InputError(file, field, "dims too large for CELL_DATA (DIMENSIONS = dims + 1)");
  }
}

}  // namespace

ConcentrationFrame read_vtk_structured_points(const std::filesystem::path& path, double time_s,
                                              const VtkArrayNames& names) {
  const std::string file = path.string();
  check_names(file, names);
  if (!std::isfinite(time_s)) throw InputError(file, "time", "time must be finite");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "", "file not found");
  VtkParser parser(path, names);
  return parser.run(time_s);
}

ConcentrationSeries read_vtk_series(
    const std::vector<std::pair<double, std::string>>& time_and_path, const VtkArrayNames& names) {
  if (time_and_path.empty()) throw InputError("", "", "a VTK series needs at least one file");
  // Times first: they are cheap to check and an unsorted list is a caller
  // error that reading gigabytes would only delay.
  for (std::size_t i = 0; i < time_and_path.size(); ++i) {
    const auto& [t, p] = time_and_path[i];
    if (!std::isfinite(t))
      throw InputError(p, fmt::format("time[{}]", i), fmt::format("time {} s is not finite", t));
    if (i > 0 && !(t > time_and_path[i - 1].first))
      throw InputError(p, fmt::format("time[{}]", i),
                       fmt::format("time {} s is not after the previous frame's {} s ({}): "
                                   "times must be strictly increasing",
                                   t, time_and_path[i - 1].first, time_and_path[i - 1].second));
  }
  ConcentrationSeries series;
  series.source = time_and_path.front().second;
  if (time_and_path.size() > 1)
    series.source += fmt::format(" (+{} files)", time_and_path.size() - 1);
  for (const auto& [t, p] : time_and_path) {
    ConcentrationFrame frame = read_vtk_structured_points(p, t, names);
    if (!series.frames.empty()) {
      const ScalarGrid& a = series.frames.front().concentration_g_m3;
      const ScalarGrid& b = frame.concentration_g_m3;
      const double h = a.placement.voxel_size_m;
      const Vec3 d = b.placement.origin_m - a.placement.origin_m;
      const bool same =
          a.dims == b.dims && std::abs(b.placement.voxel_size_m - h) <= kSameGridTolerance * h &&
          std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) <= kSameGridTolerance * h;
      if (!same)
        throw InputError(
            p, "grid",
            fmt::format("grid {}x{}x{} voxels of {} m at ({}, {}, {}) differs from the first "
                        "frame's {}x{}x{} of {} m at ({}, {}, {}) ({}): every frame of a series "
                        "must share one grid",
                        b.dims.nx, b.dims.ny, b.dims.nz, b.placement.voxel_size_m,
                        b.placement.origin_m.x, b.placement.origin_m.y, b.placement.origin_m.z,
                        a.dims.nx, a.dims.ny, a.dims.nz, h, a.placement.origin_m.x,
                        a.placement.origin_m.y, a.placement.origin_m.z,
                        time_and_path.front().second));
      // Bit-identical placement for every frame, so that downstream code may
      // compare placements exactly.
      frame.concentration_g_m3.placement = a.placement;
      if (frame.temperature_k) frame.temperature_k->placement = a.placement;
    }
    series.frames.push_back(std::move(frame));
  }
  return series;
}

void write_vtk_structured_points(const std::filesystem::path& path,
                                 const std::vector<VtkScalarArray>& arrays, VtkEncoding encoding,
                                 VtkDataLocation location) {
  const std::string file = path.string();
  check_arrays(file, arrays, location);
  const ScalarGrid& g = *arrays.front().grid;
  const double h = g.placement.voxel_size_m;
  const bool points = location == VtkDataLocation::kPoints;
  // Points sit at voxel centres; cells are the voxels (see the header).
  const Vec3 origin = points ? g.placement.origin_m + Vec3(h, h, h) * 0.5 : g.placement.origin_m;
  const int add = points ? 0 : 1;

  AtomicFile atomic(path);
  OutFile out(atomic.temp_path());
  out.write(
      fmt::format("# vtk DataFile Version 3.0\n"
                  "obscura scalar grid\n"
                  "{}\n"
                  "DATASET STRUCTURED_POINTS\n"
                  "DIMENSIONS {} {} {}\n"
                  "ORIGIN {} {} {}\n"
                  "SPACING {} {} {}\n"
                  "{} {}\n",
                  encoding == VtkEncoding::kAscii ? "ASCII" : "BINARY", g.dims.nx + add,
                  g.dims.ny + add, g.dims.nz + add, origin.x, origin.y, origin.z, h, h, h,
                  points ? "POINT_DATA" : "CELL_DATA", g.dims.count()));
  for (const VtkScalarArray& a : arrays) {
    out.write(fmt::format("SCALARS {} float 1\nLOOKUP_TABLE default\n", encode_name(a.name)));
    const std::vector<float>& v = a.grid->values;
    if (encoding == VtkEncoding::kAscii) {
      fmt::memory_buffer buf;
      for (std::size_t i = 0; i < v.size(); ++i) {
        // fmt prints the shortest decimal form that reads back to the same float.
        fmt::format_to(std::back_inserter(buf), "{}{}", v[i],
                       (i % 9 == 8 || i + 1 == v.size()) ? '\n' : ' ');
        if (buf.size() > (1 << 20)) {
          out.write(buf.data(), buf.size());
          buf.clear();
        }
      }
      out.write(buf.data(), buf.size());
    } else {
      std::vector<unsigned char> buf;
      buf.reserve(std::min<std::size_t>(v.size(), 1 << 18) * 4);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::uint32_t u = std::bit_cast<std::uint32_t>(v[i]);
        buf.push_back(static_cast<unsigned char>(u >> 24));
        buf.push_back(static_cast<unsigned char>(u >> 16));
        buf.push_back(static_cast<unsigned char>(u >> 8));
        buf.push_back(static_cast<unsigned char>(u));
        if (buf.size() >= (1u << 20)) {
          out.write(buf.data(), buf.size());
          buf.clear();
        }
      }
      out.write(buf.data(), buf.size());
      out.write("\n");
    }
  }
  out.close();
  atomic.commit();
}

void write_vtk_frame(const std::filesystem::path& path, const ConcentrationFrame& frame,
                     VtkEncoding encoding, VtkDataLocation location) {
  std::vector<VtkScalarArray> arrays{{"concentration", &frame.concentration_g_m3}};
  if (frame.temperature_k) arrays.push_back({"temperature", &*frame.temperature_k});
  write_vtk_structured_points(path, arrays, encoding, location);
}

}  // namespace obscura
