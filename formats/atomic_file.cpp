#include "formats/atomic_file.h"

#include <unistd.h>

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

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw Error(target_.string() + ": cannot write: " + ec.message());
  committed_ = true;
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
