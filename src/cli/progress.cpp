#include "cli/progress.h"

#include <cmath>
#include <cstdio>

#include <unistd.h>

namespace bluetile::cli {

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)),
      total_(total),
      enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

std::string duration_words(double seconds) {
  char text[48];
  if (seconds < 90.0) std::snprintf(text, sizeof text, "%.0f s", std::ceil(seconds));
  else if (seconds < 90.0 * 60.0) std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  else if (seconds < 48.0 * 3600.0) std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  else std::snprintf(text, sizeof text, "%.0f days", seconds / 86400.0);
  return text;
}

std::string time_left(double elapsed_s, long long done, long long total) {
  // Too early for a rate worth showing: under a second or nothing done yet.
  if (done <= 0 || done >= total || elapsed_s < 1.0) return "";
  const double left_s = elapsed_s * static_cast<double>(total - done) / static_cast<double>(done);
  return ", about " + duration_words(left_s) + " left";
}

Progress::~Progress() { finish(); }

void Progress::update(long long done, const std::string& detail) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  if (total_ <= 0) std::fprintf(stderr, "\r\033[K%s %s", label_.c_str(), detail.c_str());  // a step, no count
  else {
    const double elapsed_s = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r\033[K%s %lld/%lld%s %s", label_.c_str(), done, total_,
                 time_left(elapsed_s, done, total_).c_str(), detail.c_str());
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
}

}  // namespace bluetile::cli
