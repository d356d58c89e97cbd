#pragma once
/// The bytes of the files a command read its inputs from (a scene, the meshes it names, a
/// solution), by the path it named them with. Over an MPI job one process reads them once and
/// hands them to the others (distributed/, cli/inputs.h), which parse the same bytes from here
/// instead of the file system: nodes need no shared file system, and every process builds the
/// same scene.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace rad {

/// Checks that `file` is a file a command can read whole: it exists and is a regular file (a
/// FIFO would block forever, a folder is not a file, a device never ends), following symlinks.
/// Then records it as an input of this process: no output may be written over it
/// (formats/atomic_file.h). Throws InputError "FILE: cannot open WHAT: REASON", the reason the
/// system's ("No such file or directory") or the kind of file ("a FIFO, not a regular file").
void check_input_file(const std::filesystem::path& file, const std::string& what);

/// The recorded input that is the same file (device and inode) as `file`, if any.
std::optional<std::filesystem::path> recorded_input(const std::filesystem::path& file);

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
