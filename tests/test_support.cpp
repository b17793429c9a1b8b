#include "test_support.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"

namespace bluetile::test {

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "bluetile-test-XXXXXX").string();
  path_ = mkdtemp(pattern.data());
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  std::ofstream(file(name), std::ios::binary) << text;
  return file(name);
}

std::vector<std::string> TempDir::list() const {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path_)) names.push_back(entry.path().filename().string());
  return names;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_bluetile(const std::vector<std::string>& arguments, const std::string& environment) {
  std::string command = environment + " '" BLUETILE_BINARY "'";
  for (const auto& a : arguments) {
    std::string quoted;
    for (char c : a) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    command += " '" + quoted + "'";
  }
  return run_command(command);
}

CommandResult run_command(const std::string& shell_command) {
  TempDir capture;
  const std::string command = shell_command + " </dev/null >'" + capture.file("out") + "' 2>'" + capture.file("err") + "'";
  int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_text(capture.file("out"));
  result.err = read_text(capture.file("err"));
  return result;
}

std::vector<Point> uniform_points(std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> points(count);
  for (Point& p : points) p = rng.point(Domain{});
  return points;
}

bool identical_cells(const SceneCells& a, const SceneCells& b) {
  if (a.cells.size() != b.cells.size()) return false;
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    const Cell &x = a.cells[i], &y = b.cells[i];
    const double fx[6] = {x.centroid.x, x.centroid.y, x.area, x.mass, x.second_moment, x.radius};
    const double fy[6] = {y.centroid.x, y.centroid.y, y.area, y.mass, y.second_moment, y.radius};
    if (std::memcmp(fx, fy, sizeof fx) != 0 || x.status != y.status) return false;
  }
  return true;
}

namespace {

// PNG's chunk checksum (ISO 3309 CRC-32, as the PNG specification defines it), for headers
// patched by hand.
std::uint32_t png_crc(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

}  // namespace

std::string with_png_size(std::string png, std::uint32_t width, std::uint32_t height) {
  auto put = [&](std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) png[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (24 - 8 * i)) & 0xFF);
  };
  // Signature (8), IHDR length (4), "IHDR" at 12, width at 16, height at 20, 5 more bytes, CRC at 29.
  put(16, width);
  put(20, height);
  put(29, png_crc(png.substr(12, 17)));
  return png;
}

}  // namespace bluetile::test
