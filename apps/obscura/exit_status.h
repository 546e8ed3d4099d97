#pragma once
// The tool's exit statuses, one meaning each (README "Exit status", docs/errors.md).
namespace obscura::cli {

inline constexpr int kExitInputError = 1;  // bad input: a file, a field, an option value
inline constexpr int kExitInternal = 2;    // a bug in obscura (InternalError, OBSCURA_CHECK)
inline constexpr int kExitUsage = 64;      // the command line itself (BSD sysexits EX_USAGE)

}  // namespace obscura::cli
