#pragma once
// Provenance stored in every output (EXR header attribute, PNG text chunk,
// JSON sidecar), so a result can be traced to the exact software version,
// command line, random seed and input files (by content hash) that made it.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace obscura {

struct InputHash {
  std::string path;    // as given on the command line or in the scene
  std::string sha256;  // 64 lowercase hex digits of the file's content
};

struct Provenance {
  std::string software = "obscura";
  std::string version;
  std::string command_line;
  std::uint64_t seed = 0;
  std::vector<InputHash> inputs;
  std::string created_utc;  // ISO 8601, e.g. "2024-05-01T12:34:56Z"

  nlohmann::json to_json() const;
  // Compact (single-line) JSON of to_json().
  std::string to_string() const;
  // Inverse of to_json(); throws obscura::Error on a missing or mistyped key.
  static Provenance from_json(const nlohmann::json& value);
};

// SHA-256 of a file's content as 64 lowercase hex digits.
// Throws InputError(path, "", "cannot read file: <reason>") if unreadable.
std::string sha256_file(const std::filesystem::path& path);
// SHA-256 of `bytes` as 64 lowercase hex digits.
std::string sha256_bytes(std::string_view bytes);

// argv joined by spaces; arguments that a POSIX shell would split or expand
// are single-quoted, so the result can be pasted back into a shell.
std::string join_command_line(int argc, const char* const* argv);

// The current UTC time in ISO 8601 with second resolution ("...Z").
std::string utc_now_iso8601();

// Fills version from obscura::kVersion, hashes every input and stamps the
// current UTC time. Throws InputError if an input cannot be read.
Provenance make_provenance(std::string command_line, std::uint64_t seed,
                           const std::vector<std::filesystem::path>& inputs);

}  // namespace obscura
