#include "obscura/io/text_lines.h"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/input_file.h"

namespace obscura {

std::string read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                           std::string_view what) {
  const std::string file = path.string();
  require_regular_file(path, what);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(file, "", fmt::format("cannot open {}: {}", what, ec.message()));
  if (size > max_bytes)
    throw InputError(
        file, "",
        fmt::format("the {} is {} bytes, more than the {} accepted", what, size, max_bytes));
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(text.data(), static_cast<std::streamsize>(size)))
    throw InputError(file, "", fmt::format("cannot read {}", what));
  return text;
}

bool TextLines::next(std::string_view& line) {
  if (done_) return false;
  const std::size_t end = rest_.find_first_of("\r\n");
  if (end == std::string_view::npos) {  // the last line, without an end
    done_ = true;
    if (rest_.empty()) return false;
    line = rest_;
    ++number_;
    return true;
  }
  line = rest_.substr(0, end);
  const bool crlf = rest_[end] == '\r' && end + 1 < rest_.size() && rest_[end + 1] == '\n';
  rest_.remove_prefix(end + (crlf ? 2 : 1));
  ++number_;
  return true;
}

std::optional<double> parse_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ptr != token.data() + token.size()) return std::nullopt;
  // Out of range: strtod gives ±inf for an overflow (refused by the callers
  // as not finite) and 0 or a subnormal for an underflow.
  if (ec == std::errc::result_out_of_range) return std::strtod(std::string(token).c_str(), nullptr);
  if (ec != std::errc()) return std::nullopt;
  return v;
}

std::string_view trim(std::string_view s) {
  const std::size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const std::size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

}  // namespace obscura
