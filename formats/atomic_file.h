#pragma once
/// Writing outputs so that nothing a user has is lost: write a temporary file beside the target
/// and rename it over the target only when writing succeeded.
#include <filesystem>
#include <functional>
#include <ostream>

namespace rad {

/// Usage: AtomicFile out(path); write to out.temp_path(); out.commit();
/// Creates the target's folder if needed. If commit() is never reached (an exception), the
/// destructor removes the temporary file and the target is untouched.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// A path in the target's folder, with the target's extension (some writers look at it).
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  /// Renames the temporary file onto the target (atomic on one file system: a reader, or a
  /// process killed at any moment, sees the old file or the new one whole; of two processes
  /// writing one target, the last rename wins). Then removes temporaries of this target left by
  /// processes that no longer run. Throws Error.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

/// Writes a text file through an AtomicFile: `write` fills the stream; a failed write throws
/// Error naming the target, and the target is then untouched.
void write_text_file(const std::filesystem::path& target,
                     const std::function<void(std::ostream&)>& write);

}  // namespace rad
