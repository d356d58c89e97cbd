#pragma once
/// Exception types shared by every module. Library code throws; only `main` prints and exits.
#include <stdexcept>
#include <string>

namespace rad {

/// Base of every error this project throws on purpose. `what()` is one line a user can act on.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Bad user input: an unreadable or malformed file, or a value outside its domain. The message
/// names the file and the element ("scene.json: objects[2] polygon 5: zero area").
class InputError : public Error {
 public:
  using Error::Error;
};

}  // namespace rad
