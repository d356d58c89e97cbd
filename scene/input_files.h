#pragma once
/// The bytes of the files a command read its inputs from (a scene, the meshes it names, a
/// solution), by the path it named them with. Over an MPI job one process reads them once and
/// hands them to the others (distributed/, cli/inputs.h), which parse the same bytes from here
/// instead of the file system: nodes need no shared file system, and every process builds the
/// same scene.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace rad {

class InputFiles {
 public:
  /// The bytes recorded for `file`, or nullptr when it was not recorded.
  const std::string* find(const std::filesystem::path& file) const;
  void add(const std::filesystem::path& file, std::string bytes);
  /// Reads `file` whole from disk and records it; throws InputError naming `what` and the file
  /// when it cannot.
  const std::string& read(const std::filesystem::path& file, const std::string& what);

  /// All files as one byte string, and back (throws Error on bytes that are not one).
  std::string serialize() const;
  static InputFiles deserialize(std::string_view bytes);

 private:
  std::map<std::string, std::string> files_;
};

}  // namespace rad
