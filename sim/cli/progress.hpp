// A progress bar on stderr when it is a terminal; silent otherwise (CI logs, pipes).
#pragma once

#include <cstddef>
#include <string>

namespace bimloc::cli {

class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();  // clears the bar's line
  void update(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool enabled_ = false;
  int last_percent_ = -1;
};

}  // namespace bimloc::cli
