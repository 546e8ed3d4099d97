#include "obscura/io/vtk_data_arrays.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <utility>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"

namespace obscura::vtk_legacy {

std::string ArrayDecl::describe() const {
  return fmt::format("{} '{}' ({}, {} x {} {})", keyword, name, section_keyword(section), tuples,
                     components, type.name);
}

bool ArrayReader::is_selected(const std::string& name) const {
  return name == names_.concentration ||
         (!names_.temperature.empty() && name == names_.temperature);
}

std::uint64_t ArrayReader::value_count(const ArrayDecl& a) const {
  std::uint64_t count = 0;
  if (__builtin_mul_overflow(a.tuples, a.components, &count))
    tokens_.fail(a.at, fmt::format("{} has {} x {} values, which overflows a 64-bit count",
                                   a.describe(), a.tuples, a.components));
  return count;
}

void ArrayReader::take(const ArrayDecl& a) {
  if (a.section != Section::kNone) found_.push_back(a);
  last_array_ = a.describe();
  if (a.section == Section::kNone || !is_selected(a.name)) {
    skip(a);
    return;
  }
  const bool is_conc = a.name == names_.concentration;
  std::optional<SelectedArray>& slot = is_conc ? concentration_ : temperature_;
  check_selectable(a, slot, is_conc);
  const std::uint64_t count = value_count(a);
  check_memory(a, count);
  SelectedArray sel;
  sel.section = a.section;
  sel.at = a.at;
  check_available(a, count);
  sel.values.resize(static_cast<std::size_t>(count));
  read_values(a, count, sel.values.data());
  slot = std::move(sel);
}

// One concentration or temperature array, of one numeric component.
void ArrayReader::check_selectable(const ArrayDecl& a, const std::optional<SelectedArray>& slot,
                                   bool is_conc) const {
  if (slot)
    tokens_.fail(a.at, fmt::format("a second array named '{}' ({} has one already): the choice "
                                   "would be ambiguous",
                                   a.name, Lexer::where(slot->at)));
  if (a.components != 1)
    tokens_.fail(a.at,
                 fmt::format("{} has {} components per value; a {} array must have 1", a.describe(),
                             a.components, is_conc ? "concentration" : "temperature"));
  if (a.type.kind == ValueKind::kBit)
    tokens_.fail(a.at, fmt::format("{} is a bit array; a {} must be numeric", a.describe(),
                                   is_conc ? "concentration" : "temperature"));
}

// Memory first, before a byte is allocated: a corrupt or hostile header
// must produce a message, not std::bad_alloc or the OOM killer.
void ArrayReader::check_memory(const ArrayDecl& a, std::uint64_t count) const {
  std::uint64_t bytes = 0, already = 0;
  if (concentration_) already += concentration_->values.size() * sizeof(float);
  if (temperature_) already += temperature_->values.size() * sizeof(float);
  if (__builtin_mul_overflow(count, sizeof(float), &bytes) ||
      bytes + already > memory_limit_bytes()) {
    const GridDims& d = *geometry_.dims();
    tokens_.fail(
        a.at,
        fmt::format("{} on DIMENSIONS {} {} {} needs {:.3g} GiB but only {}{}", a.describe(), d.nx,
                    d.ny, d.nz, static_cast<double>(count) * sizeof(float) / 1073741824.0,
                    memory_limit_text(),
                    already > 0 ? fmt::format(" ({:.3g} GiB already read)", already / 1073741824.0)
                                : std::string()));
  }
}

// Before allocating: the bytes the values need must be in the file. Binary
// values have a fixed size; ASCII ones need at least one character and a
// separator each.
void ArrayReader::check_available(const ArrayDecl& a, std::uint64_t count) {
  Lexer& lex = tokens_.lexer();
  if (tokens_.binary()) {
    if (count == 0) return;
    lex.finish_line();
    const std::uint64_t start = lex.offset();
    const std::uint64_t need = binary_bytes(a, count);
    if (lex.remaining() < need)
      throw InputError(
          lex.file(), fmt::format("byte {}", start),
          fmt::format("{}: truncated binary data: {} {} values need {} bytes from byte offset "
                      "{}, but the file ends at byte {} ({} bytes short)",
                      a.describe(), count, a.type.name, need, start, lex.file_size(),
                      need - lex.remaining()));
  } else if (count > 0 && count > (lex.remaining() + 1) / 2) {
    tokens_.fail(a.at,
                 fmt::format("{}: {} values cannot fit in the {} bytes left in the file (each "
                             "needs a digit and a separator): the file is truncated or {} is "
                             "wrong",
                             a.describe(), count, lex.remaining(), section_keyword(a.section)));
  }
}

std::uint64_t ArrayReader::binary_bytes(const ArrayDecl& a, std::uint64_t count) const {
  if (a.type.kind == ValueKind::kBit) return (count + 7) / 8;
  std::uint64_t need = 0;
  if (__builtin_mul_overflow(count, static_cast<std::uint64_t>(a.type.bytes), &need))
    tokens_.fail(a.at, fmt::format("{}: byte count overflows", a.describe()));
  return need;
}

// check_available() has consumed the header line and checked the size.
void ArrayReader::read_binary_values(const ArrayDecl& a, std::uint64_t count, float* out) {
  std::vector<unsigned char> chunk(static_cast<std::size_t>(a.type.bytes) * 65536);
  std::uint64_t done = 0;
  while (done < count) {
    const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(65536, count - done));
    const std::size_t nbytes = k * static_cast<std::size_t>(a.type.bytes);
    if (tokens_.lexer().read(chunk.data(), nbytes) != nbytes)
      tokens_.fail_here(fmt::format("{}: file ends inside the binary data (after {} of {} values)",
                                    a.describe(), done, count));
    for (std::size_t i = 0; i < k; ++i)
      out[done + i] = static_cast<float>(binary_value(a.type, chunk.data() + i * a.type.bytes));
    done += k;
  }
}

// `out` null: the values are parsed (so that errors are found) and dropped.
void ArrayReader::read_values(const ArrayDecl& a, std::uint64_t count, float* out) {
  if (tokens_.binary()) {
    read_binary_values(a, count, out);
    return;
  }
  Token t;
  for (std::uint64_t i = 0; i < count; ++i) {
    if (!tokens_.lexer().next(t))
      tokens_.fail_at_end(
          fmt::format("{}: file ends after {} of {} values: the file is truncated or the "
                      "{} count is wrong",
                      a.describe(), i, count, section_keyword(a.section)));
    const auto v = parse_ascii_value(a.type, t.text);
    if (!v)
      tokens_.fail(t, fmt::format("{}: '{}' is not a {} value (value {} of {}){}", a.describe(),
                                  t.text, a.type.name, i, count,
                                  std::isalpha(static_cast<unsigned char>(t.text[0]))
                                      ? ": the array has fewer values than declared"
                                      : ""));
    if (out != nullptr) out[i] = static_cast<float>(*v);
  }
}

void ArrayReader::skip(const ArrayDecl& a) {
  const std::uint64_t count = value_count(a);
  if (tokens_.binary()) {
    if (count == 0) return;
    check_available(a, count);  // consumes the header line
    tokens_.lexer().skip(binary_bytes(a, count));
    return;
  }
  ValueType parse_as = a.type;
  if (parse_as.kind == ValueKind::kBit) parse_as = *parse_value_type("int");
  ArrayDecl as_read = a;
  as_read.type = parse_as;
  read_values(as_read, count, nullptr);
}

std::string ArrayReader::list_found() const {
  if (found_.empty()) return "the file has no POINT_DATA or CELL_DATA arrays";
  std::string s = "arrays in the file: ";
  for (std::size_t i = 0; i < found_.size(); ++i) s += (i ? ", " : "") + found_[i].describe();
  return s;
}

}  // namespace obscura::vtk_legacy
