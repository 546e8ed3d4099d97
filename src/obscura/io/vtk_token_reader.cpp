#include "obscura/io/vtk_token_reader.h"

#include <cmath>

#include "obscura/core/error.h"

namespace obscura::vtk_legacy {

void TokenReader::fail(const Token& t, const std::string& what) const {
  throw InputError(lex_.file(), Lexer::where(t), what);
}

void TokenReader::fail_here(const std::string& what) const {
  throw InputError(lex_.file(), lex_.where(), what);
}

void TokenReader::fail_at_end(const std::string& what) const {
  throw InputError(lex_.file(), lex_.where_end(), what);
}

Token TokenReader::expect_token(const std::string& what) {
  Token t;
  if (!lex_.next(t)) fail_at_end(fmt::format("file ends where {} was expected", what));
  return t;
}

double TokenReader::expect_double(const std::string& what) {
  const Token t = expect_token(what);
  const auto v = parse_ascii_value(ValueType{"double", ValueKind::kDouble, 8}, t.text);
  if (!v) fail(t, fmt::format("expected {} (a number), found '{}'", what, t.text));
  if (!std::isfinite(*v)) fail(t, fmt::format("{} is {}, not a finite number", what, t.text));
  return *v;
}

ValueType TokenReader::expect_type() {
  const Token t = expect_token("a data type");
  const auto type = parse_value_type(t.text);
  if (!type)
    fail(t, fmt::format("data type '{}' is not supported (expected float, double, char, "
                        "unsigned_char, short, unsigned_short, int, unsigned_int, long, "
                        "unsigned_long, vtktypeint64, vtktypeuint64, vtkIdType or bit)",
                        t.text));
  return *type;
}

void TokenReader::skip_metadata() {
  lex_.finish_line();
  while (const auto line = lex_.read_line()) {
    if (line->find_first_not_of(" \t\r") == std::string::npos) break;
  }
}

}  // namespace obscura::vtk_legacy
