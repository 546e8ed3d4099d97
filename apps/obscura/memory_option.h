#pragma once
// --max-memory on the commands that read sizes from files (render, prepare,
// validate): the limit every such size is checked against before it is
// allocated (core/memory_limit.h). It wins over a scene's "max_memory".
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"

namespace obscura::cli {

inline void add_max_memory_option(CLI::App* cmd, const std::shared_ptr<std::string>& text) {
  cmd->add_option("--max-memory", *text,
                  fmt::format("Largest memory to take, e.g. 4GiB or 500MB (default: {:.0f}% of "
                              "the memory available when the command starts)",
                              100 * kDefaultMemoryFraction));
}

// Sets the limit when the option was given; a bad size is an input error naming it.
inline void apply_max_memory(const std::string& text) {
  if (text.empty()) return;
  const auto bytes = parse_memory_size(text);
  if (!bytes)
    throw InputError("", "--max-memory",
                     fmt::format("'{}' is not a memory size (expected e.g. 4GiB or 500MB)", text));
  set_memory_limit(*bytes, MemoryLimitSource::kCommandLine);
}

}  // namespace obscura::cli
