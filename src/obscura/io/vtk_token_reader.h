#pragma once
// The token layer of the VTK STRUCTURED_POINTS reader (io/vtk_structured_points.h):
// the lexer of the file, whether its data blocks are BINARY, and "expect a
// token of this kind" helpers whose errors name the file and the place (a
// line, or a byte offset once binary data has been crossed). Internal to io/.
#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <string>
#include <system_error>

#include "obscura/io/vtk_legacy_lexer.h"

namespace obscura::vtk_legacy {

class TokenReader {
 public:
  explicit TokenReader(const std::filesystem::path& path) : lex_(path, path.string()) {}

  Lexer& lexer() { return lex_; }
  const Lexer& lexer() const { return lex_; }
  const std::string& file() const { return lex_.file(); }

  // The header's ASCII | BINARY: how the values of every array are stored.
  bool binary() const { return binary_; }
  void set_binary(bool binary) { binary_ = binary; }

  // InputError at token t, at the current position, or at the end of the file.
  [[noreturn]] void fail(const Token& t, const std::string& what) const;
  [[noreturn]] void fail_here(const std::string& what) const;
  [[noreturn]] void fail_at_end(const std::string& what) const;

  // The next token; `what` names it in the error at the end of the file.
  Token expect_token(const std::string& what);
  // An integer token in [min_value, max_value].
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
  // A finite number.
  double expect_double(const std::string& what);
  // A data type name (float, double, int, ...).
  ValueType expect_type();

  // METADATA blocks (VTK ≥ 5.1) are text up to the next blank line.
  void skip_metadata();

 private:
  Lexer lex_;
  bool binary_ = false;
};

}  // namespace obscura::vtk_legacy
