#pragma once
// Expecting an InputError and reading its file, field and message.
#include <gtest/gtest.h>

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

}  // namespace obscura::testing
