#pragma once
/// Writing outputs so that nothing a user has is lost: write a temporary file beside the target
/// and rename it over the target only when writing succeeded. A symlink is followed (its target
/// is replaced, the link kept); a character device, a FIFO or a socket is written through (the
/// bytes copied into it, the special file left as it is), as is "-", stdout. No output is
/// written over a file the process read as an input (scene/input_files.h). An interrupt
/// (SIGINT, SIGTERM, SIGHUP) removes the live temporaries before the process dies of it; after
/// a SIGKILL the next write of the same target removes them.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace rad {

/// Usage: AtomicFile out(path); write to out.temp_path(); out.commit();
/// Creates the target's folder if needed. If commit() is never reached (an exception), the
/// destructor removes the temporary file and the target is untouched.
class AtomicFile {
 public:
  /// Throws InputError when the target is a file the process read as an input, Error when no
  /// temporary can be made.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// A new file of its own (made with a unique name, O_EXCL: two processes, even in containers
  /// sharing a folder, never share one), with the target's extension (some writers look at it):
  /// beside the target, or in $TMPDIR for a special file or stdout.
  const std::filesystem::path& temp_path() const { return p_.temp; }
  /// The path as named (for messages).
  const std::filesystem::path& target() const { return p_.target; }
  /// Renames the temporary file onto the target (atomic on one file system: a reader, or a
  /// process killed at any moment, sees the old file or the new one whole; of two processes
  /// writing one target, the last rename wins), or copies it into a special file or stdout.
  /// Then removes temporaries of this target that no process holds any more. While a
  /// CommitGroup lives on this thread, the rename waits for the group's commit(). Throws Error
  /// naming the target and the system's reason.
  void commit();

  /// A temporary and where it goes.
  struct Pending {
    std::filesystem::path target;    ///< As named.
    std::filesystem::path resolved;  ///< Symlinks followed.
    std::filesystem::path temp;
    bool through = false;  ///< A special file or stdout: copy into it, never rename over it.
    int lock_fd = -1;      ///< Held on the temporary until it is renamed: it is alive.
    int slot = -1;         ///< Where an interrupt's handler finds it (-1: nowhere)
    void finish();         ///< The rename or the copy itself; then the stale temporaries go.
    void discard();        ///< Removes the temporary.
  };

 private:
  Pending p_;
  bool committed_ = false;
};

/// Outputs written as a whole: while a group lives on a thread, every AtomicFile committed on
/// that thread keeps its temporary until the group's commit() renames them all. A command that
/// writes several files (an image, its preview, its statistics) writes every temporary first,
/// so that a full disk or a failed writer leaves all of the previous files, not some of each.
class CommitGroup {
 public:
  CommitGroup();
  ~CommitGroup();  ///< Without commit(): removes the temporaries, the targets untouched.
  CommitGroup(const CommitGroup&) = delete;
  CommitGroup& operator=(const CommitGroup&) = delete;
  void commit();

 private:
  friend class AtomicFile;
  std::vector<AtomicFile::Pending> pending_;
  CommitGroup* outer_ = nullptr;
};

/// Writes a text file through an AtomicFile: `write` fills the stream; a failed write throws
/// Error naming the target, and the target is then untouched.
void write_text_file(const std::filesystem::path& target,
                     const std::function<void(std::ostream&)>& write);

/// Throws InputError, before any work, when an output (a name for messages, "-o", and its path)
/// is a file the process read as an input, or two outputs are the same file (by device and
/// inode when they exist, by their resolved paths when not), or an output can never be a file
/// (it is a folder, or under a file: a long solve would find out only at its end). Special
/// files and stdout ("-") may repeat: they are written through.
void check_outputs(const std::vector<std::pair<std::string, std::filesystem::path>>& outputs);

}  // namespace rad
