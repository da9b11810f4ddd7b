// Output that is either complete or absent: write under a temporary name, then rename.
#pragma once

#include <string>

namespace bimloc::sim {

// Writes `contents` to `path` atomically; throws std::runtime_error naming the path.
void writeFileAtomically(const std::string& path, const std::string& contents);

// What marks a folder as an earlier output of the same command: a JSON file in it whose
// "format" is `format` (building.json of bimloc.building, metadata.json of bimloc.dataset).
struct OutputKind {
  std::string marker_file;
  std::string format;
};

// An output folder filled under a temporary name beside it (.NAME.staging-PID-XXXXXX) and put
// in place by commit() with one rename, so that the final name holds the whole output or none.
// The final folder may be absent, empty, or an earlier output of the same kind, which commit()
// replaces whole (an atomic exchange of the two folders, then the old one removed); any other
// existing path is refused, at construction and again at commit. The staging folder is removed
// when the object is destroyed uncommitted (an exception on the way), on SIGINT and SIGTERM
// (interrupt_cleanup.hpp), and, after a SIGKILL or a crash, by the next StagingDirectory of the
// same final path, once the process named in it is gone.
class StagingDirectory {
 public:
  StagingDirectory(std::string final_path, OutputKind kind);
  ~StagingDirectory();
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;

  const std::string& path() const { return staging_; }  // write files here
  std::string file(const std::string& name) const { return staging_ + "/" + name; }
  void commit();

 private:
  std::string final_;
  OutputKind kind_;
  std::string staging_;
  bool committed_ = false;
};

}  // namespace bimloc::sim
