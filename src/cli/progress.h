// Progress on stderr, only when stderr is a terminal: batch runs and logs stay quiet. One line,
// cut to the terminal's width, redrawn in place (without escape sequences under TERM=dumb).
#pragma once

#include <chrono>
#include <string>

namespace bluetile::cli {

// A duration as people say it: "42 s", "12 min", "3.5 h", "40 days".
std::string duration_words(double seconds);

// ", about 3 s left" after `done` of `total` steps in elapsed_s seconds; "" before a second has
// passed or a step is done, and at the end.
std::string time_left(double elapsed_s, long long done, long long total);

class Progress {
 public:
  // total <= 0: a step without a count, shown as its label and detail.
  Progress(std::string label, long long total);
  ~Progress();
  // Shows `done` of total; redraws at most a few times a second.
  void update(long long done, const std::string& detail = {});
  void finish();

 private:
  // Shows `line` in place of the one before, cut to the terminal's width.
  void draw(std::string line);

  std::string label_;
  long long total_;
  bool enabled_;
  bool drawn_ = false;
  std::size_t columns_ = 80;  // the terminal's width
  bool dumb_ = false;         // TERM=dumb or unset: no escape sequences
  std::size_t shown_ = 0;     // dumb_: the length of the line on screen
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace bluetile::cli
