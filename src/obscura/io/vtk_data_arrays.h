#pragma once
// The data arrays of a VTK STRUCTURED_POINTS file, once their declaration is
// parsed: the concentration and temperature arrays are read (after checking
// that the memory and the file's bytes suffice), every other array is
// skipped. ASCII or BINARY values (VTK File Formats, "Dataset Attribute
// Format" and "Field Data"). Internal to io/.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "obscura/io/vtk_grid_geometry.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/io/vtk_token_reader.h"

namespace obscura::vtk_legacy {

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
  std::string describe() const;
};

// The values of the concentration or temperature array, as read.
struct SelectedArray {
  std::vector<float> values;
  Section section = Section::kNone;
  Token at;
};

class ArrayReader {
 public:
  ArrayReader(TokenReader& tokens, const VtkArrayNames& names, const GridGeometry& geometry)
      : tokens_(tokens), names_(names), geometry_(geometry) {}

  // Whether `name` is the concentration or the temperature array.
  bool is_selected(const std::string& name) const;

  // Reads the array's values if it is the concentration or temperature (each
  // at most once), skips them otherwise.
  void take(const ArrayDecl& a);
  // Skips the array's values.
  void skip(const ArrayDecl& a);

  // The last array declared, for "more values than declared".
  const std::string& last_array() const { return last_array_; }
  // The grid arrays seen so far, for "no array named ...".
  std::string list_found() const;

  std::optional<SelectedArray>& concentration() { return concentration_; }
  std::optional<SelectedArray>& temperature() { return temperature_; }

 private:
  std::uint64_t value_count(const ArrayDecl& a) const;
  void check_selectable(const ArrayDecl& a, const std::optional<SelectedArray>& slot,
                        bool is_conc) const;
  void check_memory(const ArrayDecl& a, std::uint64_t count) const;
  void check_available(const ArrayDecl& a, std::uint64_t count);
  std::uint64_t binary_bytes(const ArrayDecl& a, std::uint64_t count) const;
  void read_values(const ArrayDecl& a, std::uint64_t count, float* out);
  void read_binary_values(const ArrayDecl& a, std::uint64_t count, float* out);

  TokenReader& tokens_;
  const VtkArrayNames& names_;
  const GridGeometry& geometry_;
  std::vector<ArrayDecl> found_;
  std::string last_array_;
  std::optional<SelectedArray> concentration_, temperature_;
};

}  // namespace obscura::vtk_legacy
