#include "sim/world/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
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
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error(path + ": cannot rename into place: " + why);
  }
}

StagingDirectory::StagingDirectory(std::string final_path) : final_(std::move(final_path)) {
  while (final_.size() > 1 && final_.back() == '/') final_.pop_back();
  const std::string parent = parentOf(final_);
  std::error_code ec;
  fs::create_directories(parent, ec);
  std::string tmp = parent + "/." + fs::path(final_).filename().string() + ".tmp-XXXXXX";
  if (!::mkdtemp(tmp.data())) throw std::runtime_error(final_ + ": cannot create a staging directory: " + std::strerror(errno));
  staging_ = tmp;
}

StagingDirectory::~StagingDirectory() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void StagingDirectory::commit() {
  std::error_code ec;
  fs::create_directories(final_, ec);
  if (ec) throw std::runtime_error(final_ + ": cannot create directory: " + ec.message());
  for (const auto& entry : fs::directory_iterator(staging_)) {
    const fs::path target = fs::path(final_) / entry.path().filename();
    fs::rename(entry.path(), target, ec);
    if (ec) throw std::runtime_error(target.string() + ": cannot move into place: " + ec.message());
  }
  fs::remove(staging_, ec);
  committed_ = true;
}

}  // namespace bimloc::sim
