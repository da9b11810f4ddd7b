// Output that is either complete or absent: write under a temporary name, then rename.
#pragma once

#include <string>

namespace bimloc::sim {

// Writes `contents` to `path` atomically; throws std::runtime_error naming the path.
void writeFileAtomically(const std::string& path, const std::string& contents);

// A directory filled under a temporary name and renamed into place by commit(); removed
// with everything in it when destroyed uncommitted (an exception on the way).
class StagingDirectory {
 public:
  explicit StagingDirectory(std::string final_path);
  ~StagingDirectory();
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;

  const std::string& path() const { return staging_; }  // write files here
  std::string file(const std::string& name) const { return staging_ + "/" + name; }
  // Moves the files into the final directory (created if missing), each by rename.
  void commit();

 private:
  std::string final_;
  std::string staging_;
  bool committed_ = false;
};

}  // namespace bimloc::sim
