#pragma once
// Internal invariants (pbrt-v4 CHECK, but an exception instead of an abort:
// library code never ends the process, docs/conventions.md §10). A failed check is a bug
// in obscura, not bad input: the message names the source line and the
// condition so that a user can report it. OBSCURA_CHECK is always on and costs
// one predictable branch; OBSCURA_DCHECK is for checks too costly for release
// builds (on when NDEBUG is not defined).
#include <string>

#include "obscura/core/error.h"

namespace obscura {

// A broken internal invariant.
class InternalError : public Error {
 public:
  using Error::Error;
};

[[noreturn]] void fail_check(const char* file, int line, const char* condition,
                             const std::string& detail);

}  // namespace obscura

#define OBSCURA_CHECK(condition)                                            \
  do {                                                                      \
    if (!(condition)) [[unlikely]]                                          \
      ::obscura::fail_check(__FILE__, __LINE__, #condition, std::string()); \
  } while (false)

// The same with a message (anything convertible to std::string).
#define OBSCURA_CHECK_MSG(condition, message)                           \
  do {                                                                  \
    if (!(condition)) [[unlikely]]                                      \
      ::obscura::fail_check(__FILE__, __LINE__, #condition, (message)); \
  } while (false)

#ifdef NDEBUG
#define OBSCURA_DCHECK(condition) \
  do {                            \
  } while (false)
#else
#define OBSCURA_DCHECK(condition) OBSCURA_CHECK(condition)
#endif
