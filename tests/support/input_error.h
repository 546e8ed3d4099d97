#pragma once
// Expecting an InputError and reading its file, field and message.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "obscura/core/error.h"

namespace obscura::testing {

// Runs `fn`, which must throw InputError, and returns the error.
inline InputError expect_input_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", "", "");
}

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Writes `text` to `path` and runs `read` on it, which must throw an
// InputError naming the file, the field `field` (unless empty) and a message
// containing `detail`.
inline void expect_file_error(const std::filesystem::path& path, const std::string& text,
                              const std::function<void(const std::filesystem::path&)>& read,
                              const std::string& field, const std::string& detail) {
  std::ofstream(path, std::ios::binary) << text;
  const InputError e = expect_input_error([&] { read(path); });
  EXPECT_EQ(e.file(), path.string());
  if (!field.empty()) {
    EXPECT_EQ(e.field(), field) << e.what();
  }
  EXPECT_TRUE(contains(e.detail(), detail)) << e.what();
}

}  // namespace obscura::testing
