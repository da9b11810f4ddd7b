#include "sim/common/atomic_file.hpp"

#include "sim/common/fault_injection.hpp"
#include "sim/common/interrupt_cleanup.hpp"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <csignal>
#include <fcntl.h>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace bimloc::sim {
namespace fs = std::filesystem;

namespace {

std::string parentOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

bool isOutputOfKind(const fs::path& dir, const OutputKind& kind) {
  std::ifstream in(dir / kind.marker_file);
  if (!in) return false;
  try {
    const auto doc = nlohmann::json::parse(in);
    return doc.is_object() && doc.value("format", std::string()) == kind.format;
  } catch (const std::exception&) {
    return false;
  }
}

// Throws unless `path` is absent, an empty folder or an earlier output of the same kind.
void requireReplaceable(const std::string& path, const OutputKind& kind) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status)) throw std::runtime_error(path + ": exists and is not a directory");
  if (fs::is_empty(path, ec) && !ec) return;
  if (!isOutputOfKind(path, kind))
    throw std::runtime_error(path + ": already exists and is not an earlier " + kind.format + " output (no " +
                             kind.marker_file + " of that format in it): remove it or choose another folder");
}

// Removes the staging folders of `final_name` in `parent` whose process is gone (SIGKILL, a
// crash): their names carry the pid, and kill(pid, 0) says whether it still runs.
void removeStaleStaging(const std::string& parent, const std::string& final_name) {
  const std::string prefix = "." + final_name + ".staging-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const long pid = std::atol(name.c_str() + prefix.size());
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    fs::remove_all(entry.path(), ignored);
  }
}

}  // namespace

void writeFileAtomically(const std::string& path, const std::string& contents) {
  std::string tmp = parentOf(path) + "/." + fs::path(path).filename().string() + ".tmp-XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  std::size_t written = 0;
  while (written < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + written, contents.size() - written);
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error(path + ": write failed: " + why);
    }
    written += static_cast<std::size_t>(n);
  }
  ::fchmod(fd, 0644);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
  }
  faultPoint();
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": cannot rename into place: " + why);
  }
}

StagingDirectory::StagingDirectory(std::string final_path, OutputKind kind)
    : final_(std::move(final_path)), kind_(std::move(kind)) {
  while (final_.size() > 1 && final_.back() == '/') final_.pop_back();
  if (final_.empty()) throw std::runtime_error("empty output folder name");
  requireReplaceable(final_, kind_);
  const std::string parent = parentOf(final_);
  const std::string name = fs::path(final_).filename().string();
  if (name == "." || name == "..") throw std::runtime_error(final_ + ": name the output folder itself");
  std::error_code ec;
  fs::create_directories(parent, ec);
  removeStaleStaging(parent, name);
  std::string tmp = parent + "/." + name + ".staging-" + std::to_string(::getpid()) + "-XXXXXX";
  const auto interrupts = holdInterrupts();  // registered as soon as it exists
  if (!::mkdtemp(tmp.data())) throw std::runtime_error(final_ + ": cannot create a staging directory: " + std::strerror(errno));
  staging_ = tmp;
  registerForCleanup(staging_);
}

StagingDirectory::~StagingDirectory() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  unregisterForCleanup(staging_);
}

void StagingDirectory::commit() {
  const auto interrupts = holdInterrupts();  // an interrupt now waits for the folder to be in place
  requireReplaceable(final_, kind_);         // again: something may have appeared during the run
  faultPoint();
  if (std::rename(staging_.c_str(), final_.c_str()) != 0) {  // absent or empty: one rename
    if (errno != ENOTEMPTY && errno != EEXIST)
      throw std::runtime_error(final_ + ": cannot move the output into place: " + std::strerror(errno));
    // An earlier output: swap the two folders in one step, so that the final name never
    // holds a mixture or nothing; the old output is then under the staging name.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0) {
      if (errno != EINVAL && errno != ENOSYS)
        throw std::runtime_error(final_ + ": cannot replace the earlier output: " + std::strerror(errno));
      // A file system without the exchange: the old output aside first (the final name is
      // absent for a moment, never mixed), under a staging name that a later run removes.
      const std::string old = staging_ + "-old";
      if (std::rename(final_.c_str(), old.c_str()) != 0)
        throw std::runtime_error(final_ + ": cannot move the earlier output aside: " + std::strerror(errno));
      registerForCleanup(old);
      faultPoint();
      if (std::rename(staging_.c_str(), final_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::rename(old.c_str(), final_.c_str());  // the earlier output back, as it was
        unregisterForCleanup(old);
        throw std::runtime_error(final_ + ": cannot move the output into place: " + why);
      }
      unregisterForCleanup(staging_);
      staging_ = old;
    }
    faultPoint();
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
  committed_ = true;
  unregisterForCleanup(staging_);
}

}  // namespace bimloc::sim
