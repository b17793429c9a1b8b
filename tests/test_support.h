// Helpers shared by the test files: temporary folders and running the bluetile binary.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bluetile/core/torus.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile::test {

// A fresh, empty folder under the system temp dir, removed when the object goes.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Writes `text` to file(name) and returns its path.
  std::string write(const std::string& name, const std::string& text) const;
  // Names of the files in the folder (to check nothing was left behind).
  std::vector<std::string> list() const;

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs the bluetile binary with `arguments` (shell-quoted here), stdin from /dev/null;
// `environment`: NAME=value words before it (quote the values yourself).
CommandResult run_bluetile(const std::vector<std::string>& arguments, const std::string& environment = "");

// Runs a shell command line (quote its words yourself), stdin from /dev/null; exit code 127
// when the shell cannot find the program.
CommandResult run_command(const std::string& shell_command);

std::string read_text(const std::string& path);

// The message of the bluetile::Error that f throws, or "" when it throws none.
std::string error_of(const std::function<void()>& f);

std::vector<Point> uniform_points(std::size_t count, std::uint64_t seed);

// True when every field of every cell is the same bits (fields compared one by one: memcmp of
// the cells would also compare padding bytes).
bool identical_cells(const SceneCells& a, const SceneCells& b);

// `png` (a PNG file's bytes) with the IHDR chunk's width and height replaced and its checksum
// fixed: a header that claims a size the data does not have.
std::string with_png_size(std::string png, std::uint32_t width, std::uint32_t height);

}  // namespace bluetile::test
