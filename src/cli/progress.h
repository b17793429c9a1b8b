// Progress on stderr, only when stderr is a terminal: batch runs and logs stay quiet.
#pragma once

#include <chrono>
#include <string>

namespace bluetile::cli {

class Progress {
 public:
  // total <= 0: a step without a count, shown as its label and detail.
  Progress(std::string label, long long total);
  ~Progress();
  // Shows `done` of total; redraws at most a few times a second.
  void update(long long done, const std::string& detail = {});
  void finish();

 private:
  std::string label_;
  long long total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace bluetile::cli
