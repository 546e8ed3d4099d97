#pragma once
// JSON text parsed with the checks nlohmann's DOM parser leaves out: a key
// twice in one object is an error (the DOM keeps the last one silently),
// nesting is limited (copying or destroying a value 100 000 levels deep
// overflows the stack), and a number outside the range of a double is named
// by its JSON path instead of an internal "number overflow".
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace obscura {

// The deepest nesting of arrays and objects accepted; scenes use fewer than 10.
inline constexpr std::size_t kMaxJsonDepth = 256;

// Parses `text` (the contents of `file`, which is only named in errors).
// Throws InputError naming the file and the line and column of a syntax
// error, or the JSON path of a duplicate key, a number out of range or
// nesting deeper than kMaxJsonDepth.
nlohmann::json parse_json_document(const std::string& text, const std::string& file);

}  // namespace obscura
