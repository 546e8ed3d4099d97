#pragma once
// The tool's exit statuses, one meaning each (README "Exit status", docs/errors.md).
namespace obscura::cli {

inline constexpr int kExitInputError = 1;  // bad input: a file, a field, an option value
inline constexpr int kExitInternal = 2;    // a bug in obscura (InternalError, OBSCURA_CHECK)
// `obscura study` completed and wrote its table, but some cases failed (each
// recorded with its error).
inline constexpr int kExitCasesFailed = 3;
inline constexpr int kExitUsage = 64;  // the command line itself (BSD sysexits EX_USAGE)

}  // namespace obscura::cli
