#include "cli/progress.h"

#include <cstdio>

#include <unistd.h>

namespace bluetile::cli {

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() { finish(); }

void Progress::update(long long done, const std::string& detail) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  if (total_ <= 0) std::fprintf(stderr, "\r\033[K%s %s", label_.c_str(), detail.c_str());  // a step, no count
  else std::fprintf(stderr, "\r\033[K%s %lld/%lld %s", label_.c_str(), done, total_, detail.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
}

}  // namespace bluetile::cli
