#include "formats/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <system_error>

#include "scene/error.h"

namespace rad {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  const std::filesystem::path folder = target_.has_parent_path() ? target_.parent_path() : ".";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    throw Error(target_.string() + ": cannot create folder '" + folder.string() +
                "': " + ec.message());
  // ".name.tmpPID.ext": hidden, unique per process, and keeps the extension writers look at.
  std::string name(1, '.');
  name.append(target_.stem().string()).append(".tmp").append(std::to_string(::getpid()));
  name.append(target_.extension().string());
  temp_ = folder / name;
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
}

namespace {

/// Temporary files of this target left by processes that no longer run (killed while writing):
/// ".name.tmpPID.ext" with PID not alive. Another live process's temporary is left alone.
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
  std::string prefix(1, '.');  // built by append: GCC 12 warns falsely on "." + string
  prefix.append(target.stem().string()).append(".tmp");
  const std::string extension = target.extension().string();
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid == ::getpid() || !(::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH))
      continue;
    std::error_code ignored;
    std::filesystem::remove(entry.path(), ignored);
  }
}

}  // namespace

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw Error(target_.string() + ": cannot write: " + ec.message());
  committed_ = true;
  remove_stale_temporaries(target_);
}

void write_text_file(const std::filesystem::path& target,
                     const std::function<void(std::ostream&)>& write) {
  AtomicFile out(target);
  {
    std::ofstream file(out.temp_path());
    write(file);
    if (!file.flush()) throw Error(target.string() + ": cannot write");
  }
  out.commit();
}

}  // namespace rad
