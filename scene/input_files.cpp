#include "scene/input_files.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "scene/error.h"

namespace rad {
namespace {

void put_size(std::string& out, uint64_t n) {
  char bytes[sizeof n];
  std::memcpy(bytes, &n, sizeof n);
  out.append(bytes, sizeof n);
}

/// The next `n` bytes of `in` from `at`, which it advances; throws when `in` is too short.
std::string_view take(std::string_view in, size_t& at, uint64_t n) {
  if (n > in.size() - at) throw Error("input files: truncated bundle");
  const std::string_view out = in.substr(at, n);
  at += n;
  return out;
}

uint64_t take_size(std::string_view in, size_t& at) {
  uint64_t n = 0;
  std::memcpy(&n, take(in, at, sizeof n).data(), sizeof n);
  return n;
}

/// The inputs this process has read, by device and inode.
struct RecordedInput {
  dev_t device;
  ino_t inode;
  std::filesystem::path path;
};
std::mutex recorded_mutex;
std::vector<RecordedInput> recorded;

}  // namespace

void check_input_file(const std::filesystem::path& file, const std::string& what) {
  const std::string cannot = file.string() + ": cannot open " + what + ": ";
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throw InputError(cannot + std::strerror(errno));
  const char* kind = S_ISDIR(st.st_mode)    ? "a folder"
                     : S_ISFIFO(st.st_mode) ? "a FIFO"
                     : S_ISCHR(st.st_mode)  ? "a character device"
                     : S_ISBLK(st.st_mode)  ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : nullptr;
  if (kind) throw InputError(cannot + kind + ", not a regular file");
  const std::lock_guard lock(recorded_mutex);
  for (const RecordedInput& r : recorded)
    if (r.device == st.st_dev && r.inode == st.st_ino) return;
  recorded.push_back({st.st_dev, st.st_ino, file});
}

std::optional<std::filesystem::path> recorded_input(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return std::nullopt;
  const std::lock_guard lock(recorded_mutex);
  for (const RecordedInput& r : recorded)
    if (r.device == st.st_dev && r.inode == st.st_ino) return r.path;
  return std::nullopt;
}

const std::string* InputFiles::find(const std::filesystem::path& file) const {
  const auto it = files_.find(file.string());
  return it == files_.end() ? nullptr : &it->second;
}

void InputFiles::add(const std::filesystem::path& file, std::string bytes) {
  files_[file.string()] = std::move(bytes);
}

const std::string& InputFiles::read(const std::filesystem::path& file, const std::string& what) {
  check_input_file(file, what);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open " + what);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError(file.string() + ": cannot read " + what);
  add(file, bytes.str());
  return files_[file.string()];
}

std::string InputFiles::serialize() const {
  std::string out;
  put_size(out, files_.size());
  for (const auto& [path, bytes] : files_) {
    put_size(out, path.size());
    out += path;
    put_size(out, bytes.size());
    out += bytes;
  }
  return out;
}

InputFiles InputFiles::deserialize(std::string_view bytes) {
  InputFiles files;
  size_t at = 0;
  const uint64_t count = take_size(bytes, at);
  for (uint64_t i = 0; i < count; ++i) {
    const std::string path(take(bytes, at, take_size(bytes, at)));
    files.add(path, std::string(take(bytes, at, take_size(bytes, at))));
  }
  if (at != bytes.size()) throw Error("input files: trailing bytes in the bundle");
  return files;
}

}  // namespace rad
