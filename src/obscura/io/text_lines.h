#pragma once
// Small helpers shared by the line-based text readers (OBJ meshes, heightfield
// CSV): reading a whole file with a size limit, numbered lines, numbers.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace obscura {

// The whole file; InputError naming it when it is missing, unreadable or
// larger than `max_bytes` (checked before reading). `what` names the kind of
// file in messages ("OBJ mesh").
std::string read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                           std::string_view what);

// The lines of a text, numbered from 1; "\n", "\r\n" or "\r" ends a line.
class TextLines {
 public:
  explicit TextLines(std::string_view text) : rest_(text) {}
  // The next line (without its end) into `line`; false at the end of the text.
  bool next(std::string_view& line);
  long long number() const { return number_; }

 private:
  std::string_view rest_;
  long long number_ = 0;
  bool done_ = false;
};

// A whole token as a decimal number (a leading '+' allowed); nullopt if it is
// not a number. "nan", "inf" and overflows (as ±inf) parse, for the caller to
// refuse as not finite.
std::optional<double> parse_number(std::string_view token);

// `s` without leading and trailing spaces and tabs.
std::string_view trim(std::string_view s);

}  // namespace obscura
