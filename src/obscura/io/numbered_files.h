#pragma once
// A numbered file sequence as simulation and compositing tools write it
// ("explosion_####.vdb" → explosion_0001.vdb, explosion_0002.vdb, …; Houdini's
// $F4, Blender's cache, EmberGen's exports): one run of '#' in the file name
// stands for the frame number, zero-padded to that many digits (a longer
// number fills more digits, as Houdini writes frame 10000 of $F4).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace obscura {

struct NumberedFile {
  long long frame = 0;
  std::filesystem::path file;
};

// True when the file name of `pattern` holds a run of '#'.
bool is_numbered_pattern(const std::filesystem::path& pattern);

// The file of `frame` in the sequence `pattern`.
std::filesystem::path numbered_file(const std::filesystem::path& pattern, long long frame);

// The frames of `pattern` present in its folder, in frame order: every frame
// from `first` to `last` when given, else every matching file, which must be
// consecutive. Throws InputError(source, field, ...) when the name holds two
// runs of '#', when no file matches, and naming the first missing frame's file
// when the numbers have a gap.
std::vector<NumberedFile> find_numbered_files(const std::filesystem::path& pattern,
                                              std::optional<long long> first,
                                              std::optional<long long> last,
                                              const std::string& source, const std::string& field);

}  // namespace obscura
