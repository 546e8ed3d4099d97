#include "obscura/io/numbered_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <system_error>

#include "obscura/core/error.h"

namespace obscura {
namespace {

// The file name around its run of '#'.
struct Pattern {
  std::string prefix, suffix;
  std::size_t width = 0;
};

std::optional<Pattern> split(const std::string& name) {
  const std::size_t begin = name.find('#');
  if (begin == std::string::npos) return std::nullopt;
  const std::size_t end = name.find_first_not_of('#', begin);
  Pattern p;
  p.prefix = name.substr(0, begin);
  p.width = (end == std::string::npos ? name.size() : end) - begin;
  p.suffix = end == std::string::npos ? "" : name.substr(end);
  return p;
}

// The frame number of `name` in the sequence, if it belongs to it: digits
// in place of the run, exactly `width` of them or more without a leading zero.
std::optional<long long> frame_of(const std::string& name, const Pattern& p) {
  if (name.size() < p.prefix.size() + p.suffix.size() + p.width) return std::nullopt;
  if (name.compare(0, p.prefix.size(), p.prefix) != 0) return std::nullopt;
  if (name.compare(name.size() - p.suffix.size(), p.suffix.size(), p.suffix) != 0)
    return std::nullopt;
  const std::string digits =
      name.substr(p.prefix.size(), name.size() - p.prefix.size() - p.suffix.size());
  if (digits.size() > 18) return std::nullopt;  // beyond a long long
  if (!std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
    return std::nullopt;
  if (digits.size() > p.width && digits[0] == '0') return std::nullopt;
  return std::stoll(digits);
}

std::string frames_text(const std::vector<long long>& frames) {
  std::string out;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    out += (out.empty() ? "" : ", ") +
           (i == j ? fmt::format("{}", frames[i]) : fmt::format("{}-{}", frames[i], frames[j]));
    i = j + 1;
  }
  return out;
}

}  // namespace

bool is_numbered_pattern(const std::filesystem::path& pattern) {
  return split(pattern.filename().string()).has_value();
}

std::filesystem::path numbered_file(const std::filesystem::path& pattern, long long frame) {
  const auto p = split(pattern.filename().string());
  if (!p) return pattern;
  return pattern.parent_path() / fmt::format("{}{:0{}d}{}", p->prefix, frame, p->width, p->suffix);
}

std::vector<NumberedFile> find_numbered_files(const std::filesystem::path& pattern,
                                              std::optional<long long> first,
                                              std::optional<long long> last,
                                              const std::string& source, const std::string& field) {
  const std::string name = pattern.filename().string();
  const auto p = split(name);
  if (!p) throw InputError(source, field, fmt::format("'{}' has no run of '#'", name));
  if (p->suffix.find('#') != std::string::npos)
    throw InputError(
        source, field,
        fmt::format("'{}' holds two runs of '#'; one stands for the frame number", name));
  const std::filesystem::path folder =
      pattern.parent_path().empty() ? std::filesystem::path(".") : pattern.parent_path();
  std::error_code ec;
  std::vector<long long> frames;
  for (const auto& e : std::filesystem::directory_iterator(folder, ec))
    if (e.is_regular_file(ec))
      if (const auto f = frame_of(e.path().filename().string(), *p)) frames.push_back(*f);
  if (ec && frames.empty())
    throw InputError(
        source, field,
        fmt::format("cannot list the folder '{}' ({})", folder.string(), ec.message()));
  std::sort(frames.begin(), frames.end());
  if (frames.empty())
    throw InputError(source, field,
                     fmt::format("no file of the sequence '{}' in '{}' (expected e.g. {})", name,
                                 folder.string(), numbered_file(pattern, 1).filename().string()));
  const long long from = first.value_or(frames.front()), to = last.value_or(frames.back());
  std::vector<NumberedFile> out;
  for (long long frame = from; frame <= to; ++frame) {
    if (!std::binary_search(frames.begin(), frames.end(), frame))
      throw InputError(
          source, field,
          fmt::format("frame {} of the sequence is missing: no file {} (the folder "
                      "holds frames {})",
                      frame, numbered_file(pattern, frame).string(), frames_text(frames)));
    out.push_back({frame, numbered_file(pattern, frame)});
  }
  return out;
}

}  // namespace obscura
