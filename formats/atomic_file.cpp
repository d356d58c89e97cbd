#include "formats/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <system_error>

#include "scene/error.h"
#include "scene/input_files.h"

namespace rad {
namespace {

thread_local CommitGroup* current_group = nullptr;

/// The temporaries alive now, for a signal handler to remove: an interrupted command (Ctrl-C,
/// a batch system's SIGTERM, a closed terminal's SIGHUP) leaves its targets as they were and
/// nothing of its own beside them. Fixed slots of fixed size, because a handler may do no more
/// than read them and call unlink(); a temporary that finds no slot (more than kSlots at once,
/// or a path too long) is left to remove_stale_temporaries, as after a SIGKILL.
struct TemporarySlot {
  static constexpr size_t kPath = 4096;
  std::atomic<int> state{0};  ///< 0 free, 1 being filled, 2 holds a live temporary's path
  char path[kPath];
};
constexpr int kSlots = 64;
TemporarySlot temporary_slots[kSlots];

extern "C" void remove_temporaries_and_stop(int signal) {
  for (TemporarySlot& slot : temporary_slots) {
    if (slot.state.load() == 2) ::unlink(slot.path);
  }
  // Then die of the signal, as without the handler (the shell sees how it ended).
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

/// Installs the handler for SIGINT, SIGTERM and SIGHUP, each only where no one else handles
/// or ignores it (an MPI job's root has its own for SIGTERM; nohup ignores SIGHUP).
void install_interrupt_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction now {};
      if (::sigaction(signal, nullptr, &now) != 0 || now.sa_handler != SIG_DFL) continue;
      struct sigaction handler {};
      handler.sa_handler = remove_temporaries_and_stop;
      sigemptyset(&handler.sa_mask);
      ::sigaction(signal, &handler, nullptr);
    }
  });
}

/// The slot now holding `path`, or -1.
int register_temporary(const std::string& path) {
  install_interrupt_handler();
  if (path.size() >= TemporarySlot::kPath) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int free = 0;
    if (!temporary_slots[i].state.compare_exchange_strong(free, 1)) continue;
    std::memcpy(temporary_slots[i].path, path.c_str(), path.size() + 1);
    temporary_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void unregister_temporary(int& slot) {
  if (slot >= 0) temporary_slots[slot].state.store(0);
  slot = -1;
}

bool is_stdout(const std::filesystem::path& p) { return p == "-"; }

/// `p` with every symlink followed, also a dangling one (to the file it would create); at most
/// 40 links, as the kernel allows.
std::filesystem::path follow_symlinks(std::filesystem::path p) {
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(p, ec))) break;
    const std::filesystem::path link = std::filesystem::read_symlink(p, ec);
    if (ec) break;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(p, ec);
  return ec ? p : canonical;
}

/// True when `p` exists and is not a regular file or folder: a device, a FIFO, a socket.
bool is_special(const std::filesystem::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

/// Written through, never renamed over: stdout ("-"), what is not a regular file or folder (a
/// device, a FIFO, a socket; symlinks followed, so /dev/stdout on a pipe), and anything under
/// /dev or /proc that exists (/dev/stdout on a redirected file: the shell's file, not a rename
/// over it).
bool writes_through(const std::filesystem::path& target) {
  if (is_stdout(target) || is_special(target)) return true;
  const std::string name = target.lexically_normal().string();
  std::error_code ec;
  return (name.rfind("/dev/", 0) == 0 || name.rfind("/proc/", 0) == 0) &&
         std::filesystem::exists(target, ec);
}

/// The permissions a new file gets (0666 less the umask), or an existing target's own.
mode_t mode_for(const std::filesystem::path& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

/// ".NAME.tmp." then six characters then the extension: the temporaries of `target`.
std::string temp_prefix(const std::filesystem::path& target) {
  std::string prefix(1, '.');  // built by append: GCC 12 warns falsely on "." + string
  prefix.append(target.stem().string()).append(".tmp.");
  return prefix;
}

/// Removes temporaries of this target that no process holds (their writers were killed): a
/// writer holds an exclusive lock on its temporary until it is renamed, and the kernel drops
/// the lock with the process, so a temporary whose lock we can take is stale.
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = temp_prefix(target);
  const std::string extension = target.extension().string();
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + 6 + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const int fd = ::open(entry.path().c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
    }
    ::close(fd);
  }
}

/// Copies the file `from` into the open descriptor `to`; false with errno set on failure.
bool copy_into(const std::filesystem::path& from, int to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) return false;
  char buffer[1 << 16];
  bool ok = true;
  for (;;) {
    const ssize_t n = ::read(in, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      ok = false;
      break;
    }
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(to, buffer + done, static_cast<size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        ok = false;
        break;
      }
      done += w;
    }
    if (!ok) break;
  }
  const int saved = errno;
  ::close(in);
  errno = saved;
  return ok;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) {
  p_.target = std::move(target);
  p_.through = writes_through(p_.target);
  p_.resolved = p_.through ? p_.target : follow_symlinks(p_.target);
  if (const std::optional<std::filesystem::path> input =
          is_stdout(p_.target) ? std::nullopt : recorded_input(p_.resolved)) {
    throw InputError(p_.target.string() + ": is the input " + input->string() +
                     ", which this would overwrite; name another output");
  }
  // A special file's folder (/dev) is no place for a temporary: $TMPDIR is.
  std::filesystem::path folder;
  if (p_.through) {
    const char* tmp = std::getenv("TMPDIR");
    folder = tmp && *tmp ? tmp : "/tmp";
  } else {
    folder = p_.resolved.has_parent_path() ? p_.resolved.parent_path() : ".";
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec)
      throw Error(p_.target.string() + ": cannot create folder '" + folder.string() +
                  "': " + ec.message());
  }
  // ".NAME.tmp.XXXXXX.EXT": hidden, unique (mkstemps opens it O_EXCL), and keeps the extension.
  const std::string extension = p_.resolved.extension().string();
  std::string name = (folder / temp_prefix(p_.through ? "radiosity" : p_.resolved)).string();
  name.append("XXXXXX").append(extension);
  const int fd = ::mkstemps(name.data(), static_cast<int>(extension.size()));
  if (fd < 0) {
    throw Error(p_.target.string() + ": cannot write: cannot create a temporary in '" +
                folder.string() + "': " + std::strerror(errno));
  }
  p_.temp = name;
  p_.slot = register_temporary(name);
  p_.lock_fd = fd;
  ::flock(fd, LOCK_EX);  // ours until renamed (remove_stale_temporaries)
  if (!p_.through) ::fchmod(fd, mode_for(p_.resolved));
}

AtomicFile::~AtomicFile() {
  if (!committed_) p_.discard();
}

void AtomicFile::Pending::discard() {
  std::error_code ignored;
  if (!temp.empty()) std::filesystem::remove(temp, ignored);
  unregister_temporary(slot);
  if (lock_fd >= 0) ::close(lock_fd);
  lock_fd = -1;
}

void AtomicFile::Pending::finish() {
  const auto fail = [&](const std::string& why) {
    discard();
    throw Error(target.string() + ": cannot write: " + why);
  };
  if (through) {
    int out = 1;
    if (is_stdout(target)) {
      std::fflush(stdout);
    } else {
      out = ::open(resolved.c_str(), O_WRONLY | O_CLOEXEC);
      if (out < 0) fail(std::strerror(errno));
    }
    const bool copied = copy_into(temp, out);
    const int saved = errno;
    if (out != 1) ::close(out);
    if (!copied) fail(std::strerror(saved));
    discard();
    return;
  }
  std::error_code ec;
  std::filesystem::rename(temp, resolved, ec);
  if (ec) fail(ec.message());
  unregister_temporary(slot);  // (an interrupt between the two removes nothing: it is gone)
  ::close(lock_fd);
  lock_fd = -1;
  remove_stale_temporaries(resolved);
}

void AtomicFile::commit() {
  committed_ = true;
  if (current_group) {
    current_group->pending_.push_back(p_);  // the group owns the temporary now
    return;
  }
  p_.finish();
}

CommitGroup::CommitGroup() : outer_(current_group) { current_group = this; }

CommitGroup::~CommitGroup() {
  current_group = outer_;
  for (AtomicFile::Pending& p : pending_) p.discard();
}

void CommitGroup::commit() {
  current_group = outer_;
  // Every temporary is written: the renames need no space. On a failure the rest stay whole.
  std::vector<AtomicFile::Pending> pending = std::move(pending_);
  pending_.clear();
  for (size_t i = 0; i < pending.size(); ++i) {
    try {
      pending[i].finish();
    } catch (...) {
      for (size_t j = i + 1; j < pending.size(); ++j) pending[j].discard();
      throw;
    }
  }
}

void write_text_file(const std::filesystem::path& target,
                     const std::function<void(std::ostream&)>& write) {
  AtomicFile out(target);
  {
    std::ofstream file(out.temp_path());
    write(file);
    if (!file.flush()) throw Error(target.string() + ": cannot write: " + std::strerror(errno));
  }
  out.commit();
}

namespace {

/// Throws InputError when `resolved` can never be written as a file: it is a folder, or the
/// nearest of its folders that exists is not a folder (a file named like one of them). The same
/// words as AtomicFile's own failure later, but before a long solve or render rather than after.
void check_place(const std::string& what, const std::filesystem::path& path,
                 const std::filesystem::path& resolved) {
  std::error_code ec;
  if (std::filesystem::is_directory(resolved, ec)) {
    throw InputError(path.string() + ": " + what + " is a folder; name a file in it");
  }
  for (std::filesystem::path folder = resolved.parent_path(); !folder.empty();
       folder = folder.parent_path()) {
    const std::filesystem::file_status status = std::filesystem::status(folder, ec);
    if (std::filesystem::is_directory(status)) return;
    if (std::filesystem::exists(status)) {
      throw InputError(path.string() + ": cannot create folder '" +
                       resolved.parent_path().string() + "': " + std::strerror(ENOTDIR));
    }
    if (folder == folder.parent_path()) return;  // the root
  }
}

}  // namespace

void check_outputs(const std::vector<std::pair<std::string, std::filesystem::path>>& outputs) {
  struct Seen {
    std::string what;
    std::filesystem::path path;
  };
  std::vector<Seen> seen;
  for (const auto& [what, path] : outputs) {
    if (path.empty() || is_stdout(path)) continue;
    const std::filesystem::path resolved = follow_symlinks(path);
    if (const std::optional<std::filesystem::path> input = recorded_input(resolved)) {
      throw InputError(path.string() + ": " + what + " is the input " + input->string() +
                       ", which it would overwrite; name another output");
    }
    if (writes_through(path)) continue;
    check_place(what, path, resolved);
    for (const Seen& s : seen) {
      std::error_code ec;
      const bool same = s.path == resolved || std::filesystem::equivalent(s.path, resolved, ec);
      if (same) {
        throw InputError(path.string() + ": " + what + " is also " + s.what +
                         "; one would overwrite the other: name different files");
      }
    }
    seen.push_back({what, resolved});
  }
}

}  // namespace rad
