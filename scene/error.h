#pragma once
/// Exception types shared by every module. Library code throws; only `main` prints and exits.
#include <stdexcept>
#include <string>

namespace rad {

/// Base of every error this project throws on purpose. `what()` is one line a user can act on.
/// A NUL in the message (a name read from a file may hold one) is shown as "\\0": what() is a C
/// string, and would end there, before the problem.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(without_nul(message)) {}

 private:
  static std::string without_nul(const std::string& message) {
    if (message.find('\0') == std::string::npos) return message;
    std::string out;
    for (const char c : message) {
      if (c == '\0') {
        out.append("\\0");
      } else {
        out.push_back(c);
      }
    }
    return out;
  }
};

/// Bad user input: an unreadable or malformed file, or a value outside its domain. The message
/// names the file and the element ("scene.json: objects[2] polygon 5: zero area").
class InputError : public Error {
 public:
  using Error::Error;
};

}  // namespace rad
