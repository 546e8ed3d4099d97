#pragma once
// Number options taken as text and converted here, so that every bad value is
// an InputError naming its option (exit status 1), not a CLI11 conversion error.
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string>

#include "obscura/core/error.h"

namespace obscura::cli {

inline double parse_number(const std::string& text, const char* option) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
    throw InputError("", option, fmt::format("'{}' is not a finite number", text));
  return v;
}

}  // namespace obscura::cli
