#pragma once
// Temporaries carry the id (pid) of the run that made them: AtomicFile's
// ".<name>.tmp-<pid>-<n>" files and prepare's ".<name>.partial-<pid>" folders.
// A run that is killed (SIGKILL, power loss) cannot remove its own; the next
// run in the same folder does, leaving those of live runs alone.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>

namespace obscura {

// The run id in a temporary's file name, or empty when the name is not one.
std::optional<long> temporary_run_id(std::string_view filename);

// Removes from `dir` (not recursively) every temporary whose run is no longer
// alive. Returns how many were removed; a missing `dir` has none.
std::size_t remove_stale_temporaries(const std::filesystem::path& dir);

}  // namespace obscura
