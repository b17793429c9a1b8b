#include "cli/progress.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <sys/ioctl.h>
#include <unistd.h>

namespace bluetile::cli {

namespace {

// Columns of the terminal on stderr: its window size, else COLUMNS, else 80. A line as long
// wraps, and '\r' then goes back to its last row only: every redraw left a row behind.
std::size_t terminal_columns() {
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) {
    char* end = nullptr;
    const long value = std::strtol(columns, &end, 10);
    if (end != columns && *end == '\0' && value > 0 && value < 100000) return static_cast<std::size_t>(value);
  }
  return 80;
}

// A terminal that takes no escape sequences (TERM=dumb: Emacs' shell, some CI logs) showed the
// erase-line sequence as "^[[K".
bool dumb_terminal() {
  const char* term = std::getenv("TERM");
  return term == nullptr || *term == '\0' || std::strcmp(term, "dumb") == 0;
}

}  // namespace

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)),
      total_(total),
      enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {
  if (enabled_) {
    columns_ = terminal_columns();
    dumb_ = dumb_terminal();
  }
}

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
  std::string line = label_;
  if (total_ > 0) {  // else a step, no count
    const double elapsed_s = std::chrono::duration<double>(now - start_).count();
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain.
    line += ' ';
    line += std::to_string(done);
    line += '/';
    line += std::to_string(total_);
    line += time_left(elapsed_s, done, total_);
  }
  line += ' ';
  line += detail;
  draw(line);
}

void Progress::draw(std::string line) {
  // One column short of the width: a line that fills the last column wraps on some terminals.
  if (line.size() >= columns_) line.resize(columns_ > 1 ? columns_ - 1 : 0);
  if (dumb_) {
    // Blanks over what is left of the longer line before, instead of the erase sequence.
    const std::size_t shown = line.size();
    if (shown < shown_) line.append(shown_ - shown, ' ');
    std::fprintf(stderr, "\r%s", line.c_str());
    if (shown < shown_) std::fprintf(stderr, "\r%s", line.substr(0, shown).c_str());
    shown_ = shown;
  } else {
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
  }
  drawn_ = true;
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && drawn_) {
    if (dumb_) std::fprintf(stderr, "\r%s\r", std::string(shown_, ' ').c_str());
    else std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
  drawn_ = false;
  shown_ = 0;
}

}  // namespace bluetile::cli
