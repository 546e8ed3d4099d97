#pragma once
// Errors are exceptions at the library boundary, never exit() (docs/conventions.md §10):
// the CLI catches them, prints the message and returns a non-zero status.
#include <stdexcept>
#include <string>

namespace obscura {

// Any failure the caller can report to a user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad user input: names the file and the field (a JSON path such as
// "/sensors/0/fov_deg", a grid name such as "sigma_a_002", or "line 12").
class InputError : public Error {
 public:
  InputError(std::string file, std::string field, const std::string& what)
      : Error(compose(file, field, what)),
        file_(std::move(file)),
        field_(std::move(field)),
        detail_(what) {}

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  // The message without the file and field prefix.
  const std::string& detail() const { return detail_; }

 private:
  static std::string compose(const std::string& file, const std::string& field,
                             const std::string& what) {
    // Command-line options have no file: the message starts with the option.
    std::string msg = file;
    if (!field.empty()) msg += (msg.empty() ? "" : ": ") + field;
    return msg.empty() ? what : msg + ": " + what;
  }
  std::string file_;
  std::string field_;
  std::string detail_;
};

}  // namespace obscura
