// The tool against special and broken output paths: exit
// status, message and exactly what is left behind. Devices, FIFOs and links are made in a
// temporary folder; what needs root (mknod, mount) is skipped with a message otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::TempDir;
using Names = std::vector<std::string>;

// A small, fast relaxation: `more`, and -n 50 -k 2 --engine exact unless `more` sets them.
std::vector<std::string> relax(std::vector<std::string> more) {
  std::vector<std::string> args = {"relax"};
  for (auto [flag, value] : {std::pair{"-n", "50"}, std::pair{"-k", "2"}, std::pair{"--engine", "exact"}})
    if (std::find(more.begin(), more.end(), flag) == more.end()) args.insert(args.end(), {flag, value});
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// Opening a FIFO's write end waits for a reader: a reader that would wait for a writer that never
// comes (the tool failed first) is released by opening and closing a write end ourselves.
void release_reader(const std::string& fifo) {
  int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd >= 0) close(fd);
}

// The bytes `relax` writes for the same options to a plain file.
std::string reference_output(const std::vector<std::string>& options) {
  TempDir dir;
  std::vector<std::string> args = options;
  args.push_back("-o");
  args.push_back(dir.file("reference.txt"));
  Outcome r = run(relax(args));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_text(dir.file("reference.txt"));
}

void expect_failure(const Outcome& r, const std::string& message) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + message + "\n");
}

bool make_device(const std::string& path, unsigned major_number, unsigned minor_number) {
  return mknod(path.c_str(), S_IFCHR | 0666, makedev(major_number, minor_number)) == 0;
}

TEST(Outputs, DeviceNodesAreWrittenNotReplaced) {
  TempDir dir;
  if (!make_device(dir.file("mynull"), 1, 3) || !make_device(dir.file("myfull"), 1, 7))
    GTEST_SKIP() << "mknod needs CAP_MKNOD (root): device outputs not tested here";
  // The device node became a regular file.
  Outcome r = run(relax({"-o", dir.file("mynull"), "--log", dir.file("mynull")}));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run(relax({"-o", dir.file("myfull")}));
  expect_failure(r, dir.file("myfull") + ": cannot write: No space left on device");
  r = run(relax({"-o", dir.file("out.txt"), "--log", dir.file("myfull")}));
  expect_failure(r, dir.file("myfull") + ": cannot write: No space left on device");
  EXPECT_EQ(entries(dir.path()), (Names{"myfull%", "mynull%"}));  // out.txt not published either
  // A report on standard output, the same.
  Invocation report{{"--version"}};
  report.wrapper = {"/bin/sh", "-c", "f=\"$0\"; exec \"$@\" > \"$f\"", dir.file("myfull")};
  expect_failure(run(report), "standard output: cannot write: No space left on device");
}

TEST(Outputs, FifoGetsTheBytesAndStaysAFifo) {
  TempDir dir;
  ASSERT_EQ(mkfifo(dir.file("pipe").c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_text(dir.file("pipe")); });
  Outcome r = run(relax({"-n", "3000", "-o", dir.file("pipe")}));
  release_reader(dir.file("pipe"));
  reader.join();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(received, reference_output({"-n", "3000"}));
  EXPECT_EQ(entries(dir.path()), Names{"pipe|"});
}

TEST(Outputs, TiledPointsStreamIntoAFifoWithoutATemporaryCopy) {
  // tile wrote a FIFO's (or a device's) points into a temporary file in $TMPDIR
  // first, whole, and copied it over: as large as the output, and nothing reached the reader
  // before the end.
  // A PDF went the same way, its temporary folder in $TMPDIR (a run with a $TMPDIR it could not
  // write in failed); an SVG is now streamed too (TiledSvgIsStreamedInBoundedMemory).
  TempDir dir, tmp;
  // The columns for the point files (a drawing takes none).
  const auto tile_to = [](const std::string& name) {
    std::vector<std::string> args = {"tile", "--region", "0", "0", "4", "4"};
    if (!name.ends_with(".svg") && !name.ends_with(".pdf")) args.insert(args.end(), {"--columns", "x,y,i,j,rank"});
    return args;
  };
  for (const char* name : {"pipe.txt", "pipe.bin", "pipe.svg", "pipe.pdf"}) {
    const bool pdf = std::string(name) == "pipe.pdf";
    if (pdf && !pdf_unavailable_reason().empty()) continue;
    std::vector<std::string> args = tile_to(name);
    args.insert(args.end(), {"-o", dir.file(std::string("reference") + (name + 4))});
    ASSERT_EQ(run(args).exit_code, 0);
    const std::string reference = read_text(dir.file(std::string("reference") + (name + 4)));
    ASSERT_GT(reference.size(), 300000u);  // more than a pipe holds: the writer must stream

    const std::string fifo = dir.file(name);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    std::string received;
    Names temporary_while_reading = {"(not read)"};
    std::thread reader([&] {
      int fd = open(fifo.c_str(), O_RDONLY);
      if (fd < 0) return;
      char buffer[4096];
      bool first = true;
      for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) != 0;) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) break;
        // The writer is not done: the rest of the output is still to come through the pipe.
        if (first) temporary_while_reading = entries(tmp.path());
        first = false;
        received.append(buffer, static_cast<std::size_t>(n));
      }
      close(fd);
    });
    Invocation streamed{tile_to(name)};
    streamed.arguments.insert(streamed.arguments.end(), {"-o", fifo});
    streamed.environment = {{"TMPDIR", tmp.path()}};
    Outcome r = run(streamed);
    release_reader(fifo);
    reader.join();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(temporary_while_reading, Names{}) << name;
    if (pdf) {
      // cairo dates its documents: the same size, a whole PDF.
      EXPECT_EQ(received.size(), reference.size()) << name;
      EXPECT_EQ(received.rfind("%PDF-", 0), 0u) << name;
      EXPECT_NE(received.find("%%EOF", received.size() - 16), std::string::npos) << name;
    } else {
      EXPECT_TRUE(received == reference) << name << ": " << received.size() << " bytes, expected " << reference.size();
    }
    EXPECT_EQ(entries(tmp.path()), Names{});
  }
  // Standard output, "-" and /dev/stdout, gets the same bytes as a file.
  std::vector<std::string> args = tile_to("-");
  args.insert(args.end(), {"-o", "-"});
  EXPECT_TRUE(run(args).out == read_text(dir.file("reference.txt")));
  args.back() = "/dev/stdout";
  EXPECT_TRUE(run(args).out == read_text(dir.file("reference.txt")));
  Names expected = {"pipe.bin|", "pipe.pdf|", "pipe.svg|", "pipe.txt|", "reference.bin", "reference.pdf", "reference.svg",
                    "reference.txt"};
  if (!pdf_unavailable_reason().empty()) std::erase_if(expected, [](const std::string& e) { return e.find("pdf") != e.npos; });
  EXPECT_EQ(entries(dir.path()), expected);
}

TEST(Outputs, TiledSvgIsStreamedInBoundedMemory) {
  // An SVG of dots was built whole in memory (about 160 bytes a dot) before its first byte was
  // written: 5 x 10^5 dots under a 60 MiB address space were refused as needing 76 MiB.
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  TempDir dir;
  Invocation small{{"tile", "--region", "0", "0", "20", "20", "--density", "1250", "-o", dir.file("dots.svg")}};
  small.address_space_bytes = 60L << 20;
  small.environment = {{"BLUETILE_THREADS", "1"}};
  const Outcome r = run(small);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = read_text(dir.file("dots.svg"));
  std::size_t circles = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_GT(circles, 499000u);
  EXPECT_LT(circles, 501000u);
  EXPECT_EQ(svg.substr(svg.size() - 12), "</g>\n</svg>\n");
  EXPECT_EQ(entries(dir.path()), Names{"dots.svg"});
}

TEST(Outputs, StandardOutput) {
  const std::string expected = reference_output({});
  EXPECT_EQ(run(relax({"-o", "-"})).out, expected);
  EXPECT_EQ(run(relax({"-o", "/dev/stdout"})).out, expected);
  {
    // wang --check printed its seam check into the tile set on standard output.
    TempDir dir;
    const std::vector<std::string> wang = {"wang", "-n", "4", "-k", "1", "--warm", "0", "--check"};
    std::vector<std::string> to_file = wang;
    to_file.insert(to_file.end(), {"-o", dir.file("tiles.txt")});
    const Outcome file = run(to_file);
    ASSERT_EQ(file.exit_code, 0) << file.err;
    EXPECT_NE(file.out.find("seam check"), std::string::npos) << file.out;
    std::vector<std::string> to_stdout = wang;
    to_stdout.insert(to_stdout.end(), {"-o", "-"});
    const Outcome piped = run(to_stdout);
    EXPECT_EQ(piped.exit_code, 0) << piped.err;
    EXPECT_EQ(piped.out, read_text(dir.file("tiles.txt")));
    EXPECT_EQ(piped.err, file.out);  // the check, on stderr instead
  }
  {
    // A report on standard output that cannot be written was lost with exit status 0 (here
    // stdout closed; the device test above has a full one).
    TempDir dir;
    Invocation closed{{"wang", "-n", "4", "-k", "1", "--warm", "0", "--check", "-o", dir.file("tiles.txt")}};
    closed.wrapper = {"/bin/sh", "-c", "exec \"$0\" \"$@\" >&-"};
    const Outcome lost = run(closed);
    EXPECT_EQ(lost.exit_code, 1) << lost.err;
    EXPECT_EQ(lost.err.rfind("bluetile: standard output: cannot write: ", 0), 0u) << lost.err;
    Invocation help{{"--help"}};
    help.wrapper = closed.wrapper;
    EXPECT_EQ(run(help).exit_code, 1);
  }
  {
    // A reader that stops early (`relax -o - | head`) got "bluetile: -: cannot write: Broken
    // pipe" and status 1; a pipeline's writer stops quietly, with the status of SIGPIPE. 800 KB
    // of points: far more than the pipe holds, so the write after head has gone always fails.
    TempDir dir;
    Invocation piped{relax({"-n", "20000", "-k", "1", "--log", dir.file("log.csv"), "-o", "-"})};
    piped.wrapper = {"/bin/sh", "-c",
                     "{ \"$0\" \"$@\"; echo \"status $?\" >&2; } | head -c 100 > '" + dir.file("head.txt") + "'"};
    const Outcome r = run(piped);
    EXPECT_EQ(r.err, "status 141\n");
    EXPECT_EQ(read_text(dir.file("head.txt")), reference_output({"-n", "20000", "-k", "1"}).substr(0, 100));
    EXPECT_EQ(entries(dir.path()), Names{"head.txt"});  // the log was discarded with the run
  }
  Outcome r = run({"centroids", "-i", "-", "-o", "-", "--engine", "exact"});
  expect_failure(r, "stdin: no points");
  TempDir dir;
  Outcome image = run(relax({"-o", dir.file("p.txt"), "--id-image", "-"}));
  expect_failure(image, "-: this output cannot be standard output");
  EXPECT_EQ(entries(dir.path()), Names{});
}

TEST(Outputs, LinksAreFollowedAndPermissionsKept) {
  TempDir dir;
  fs::create_directory(dir.file("real"));
  dir.write("real/points.txt", "old\n");
  chmod(dir.file("real/points.txt").c_str(), 0600);
  fs::create_symlink("real/points.txt", dir.file("link.txt"));
  fs::create_symlink("real/fresh.txt", dir.file("dangling.txt"));
  EXPECT_EQ(run(relax({"-o", dir.file("link.txt"), "--log", dir.file("dangling.txt")})).exit_code, 0);
  EXPECT_EQ(read_text(dir.file("real/points.txt")), reference_output({}));
  EXPECT_EQ(read_text(dir.file("real/fresh.txt")).rfind("iteration,energy", 0), 0u);
  struct stat st {};
  stat(dir.file("real/points.txt").c_str(), &st);
  EXPECT_EQ(st.st_mode & 07777, 0600u);  // it became 0644
  EXPECT_EQ(entries(dir.path()), (Names{"dangling.txt@", "link.txt@", "real/", "real/fresh.txt", "real/points.txt"}));
}

TEST(Outputs, OutputsThatAreInputsOrEachOtherAreRefused) {
  TempDir dir;
  ASSERT_EQ(run(relax({"-o", dir.file("p.txt")})).exit_code, 0);
  const std::string before = read_text(dir.file("p.txt"));
  fs::create_symlink("p.txt", dir.file("alias.txt"));
  const std::string input = dir.file("p.txt");
  // --log pointed at the input replaced the input.
  Outcome r = run({"relax", "-i", input, "-k", "1", "--engine", "exact", "-o", dir.file("q.txt"), "--log", input});
  expect_failure(r, input + ": is the same file as the input " + input);
  r = run({"relax", "-i", input, "-k", "1", "--engine", "exact", "-o", dir.file("alias.txt")});
  expect_failure(r, dir.file("alias.txt") + ": is the same file as the input " + input);
  r = run({"relax", "-n", "5", "-k", "1", "--engine", "exact", "-o", dir.file("q.txt"), "--log", dir.path() + "/./q.txt"});
  expect_failure(r, dir.path() + "/./q.txt: is the same file as the output " + dir.file("q.txt"));
  r = run({"centroids", "-i", input, "--engine", "exact", "-o", input});
  expect_failure(r, input + ": is the same file as the input " + input);
  r = run({"progressive", "-i", input, "--add", "5", "-k", "1", "--engine", "exact", "-o", input});
  expect_failure(r, input + ": is the same file as the input " + input);
  EXPECT_EQ(read_text(input), before);
  EXPECT_EQ(entries(dir.path()), (Names{"alias.txt@", "p.txt"}));
}

TEST(Outputs, ImagesACommandReadsAreInputsToo) {
  // relax --density-map m.png --id-image m.png overwrote the map and exited 0.
  TempDir dir;
  const std::string map = dir.file("m.png");
  write_image_file(map, 4, 4, 1, std::vector<std::uint8_t>(16, 100));
  const std::string before = read_text(map);
  expect_failure(run(relax({"--density-map", map, "--id-image", map, "-o", dir.file("p.txt")})),
                 map + ": is the same file as the input " + map);
  // -o m.png is refused by its name, --format or not (output_names.h); under a name of no format,
  // a hard link to the map is still the map.
  expect_failure(run(relax({"--density-map", map, "-o", map, "--format", "text"})),
                 "--format text: --output '" + map + "' is named as image ('.png'); give it .txt, .dat, .pts or no "
                 "extension for text, or leave --format out");
  const std::string points_link = dir.file("m-points");
  std::filesystem::create_hard_link(map, points_link);
  expect_failure(run(relax({"--density-map", map, "-o", points_link})), points_link + ": is the same file as the input " + map);
  std::filesystem::remove(points_link);
  // A log named .png is refused by its name first (output_names.h); under a log's name, a hard
  // link to the map is still the map.
  const std::string link = dir.file("m.csv");
  std::filesystem::create_hard_link(map, link);
  expect_failure(run(relax({"--density-map", map, "--log", link, "-o", dir.file("p.txt")})),
                 link + ": is the same file as the input " + map);
  std::filesystem::remove(link);
  // Every other command that reads a file registers it the same way.
  expect_failure(run({"stipple", "--image", map, "-n", "10", "-k", "1", "-o", dir.file("p.txt"), "--png", map}),
                 map + ": is the same file as the input " + map);
  expect_failure(run({"tile", "--region", "0", "0", "1", "1", "--density-map", map, "--count", "10", "-o", map}),
                 map + ": is the same file as the input " + map);
  EXPECT_EQ(read_text(map), before);
  EXPECT_EQ(entries(dir.path()), Names{"m.png"});
}

TEST(Outputs, EveryPathIsCheckedBeforeTheWork) {
  TempDir dir;
  // --log into a missing folder failed only after the whole run.
  Outcome r = run(relax({"-k", "3", "--verbose", "-o", dir.file("p.txt"), "--log", dir.file("nodir/x.csv")}));
  expect_failure(r, dir.file("nodir/x.csv") + ": folder '" + dir.file("nodir") + "' does not exist");
  // ...and --sets with {} left the first sets when a later one failed.
  fs::create_directory(dir.file("set-2.txt"));
  r = run(relax({"--sets", "4", "-o", dir.file("set-{}.txt")}));
  expect_failure(r, dir.file("set-2.txt") + ": is a folder");
  r = run(relax({"-o", dir.path()}));
  expect_failure(r, dir.path() + ": is a folder");
  EXPECT_EQ(entries(dir.path()), Names{"set-2.txt/"});
  // '{}' with one set is replaced too (it wrote a file named "o{}.txt").
  EXPECT_EQ(run(relax({"--sets", "1", "-o", dir.file("o{}.txt")})).exit_code, 0);
  EXPECT_EQ(entries(dir.path()), (Names{"o0.txt", "set-2.txt/"}));
}

TEST(Outputs, ReadOnlyFoldersAndFiles) {
  // Run unprivileged (as nobody when the test runs as root, who could write anywhere).
  TempDir dir;
  chmod(dir.path().c_str(), 0777);
  fs::create_directory(dir.file("locked"));
  dir.write("locked/old.txt", "keep\n");
  chmod(dir.file("locked").c_str(), 0555);
  dir.write("readonly.txt", "keep\n");
  chmod(dir.file("readonly.txt").c_str(), 0444);
  Invocation r{relax({"-o", dir.file("locked/p.txt")})};
  r.unprivileged = true;
  expect_failure(run(r), dir.file("locked/p.txt") + ": cannot write in folder '" + dir.file("locked") + "': Permission denied");
  r.arguments = relax({"-o", dir.file("readonly.txt")});
  expect_failure(run(r), dir.file("readonly.txt") + ": cannot replace: Permission denied");
  EXPECT_EQ(read_text(dir.file("readonly.txt")), "keep\n");
  chmod(dir.file("locked").c_str(), 0755);
  EXPECT_EQ(entries(dir.path()), (Names{"locked/", "locked/old.txt", "readonly.txt"}));
}

TEST(Outputs, AnalyzePublishesAllOrNothing) {
  TempDir dir;
  ASSERT_EQ(run(relax({"-o", dir.file("p.txt")})).exit_code, 0);
  // A folder in the way of points.png left stats.json and radial.csv behind.
  fs::create_directories(dir.file("an/points.png"));
  Outcome r = run({"analyze", "-i", dir.file("p.txt"), "-o", dir.file("an"), "--no-centroids"});
  expect_failure(r, dir.file("an/points.png") + ": is a folder");
  EXPECT_EQ(entries(dir.file("an")), Names{"points.png/"});
  // A missing folder appears with all its files, or not at all (only the last one is created).
  fs::create_directory(dir.file("new"));
  r = run({"analyze", "-i", dir.file("p.txt"), "-o", dir.file("new/sub"), "--no-centroids"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(dir.file("new")),
            (Names{"sub/", "sub/points.png", "sub/points.svg", "sub/radial.csv", "sub/radial.png", "sub/radial.svg",
                   "sub/rdf.csv", "sub/rdf.png", "sub/rdf.svg", "sub/report.txt", "sub/spectrum.png", "sub/spectrum.svg",
                   "sub/stats.json"}));
}

TEST(Outputs, FileSizeLimitIsAWriteErrorAndLeavesNothing) {
  // ulimit -f stands in for a full disk without root: every staged write is checked, images too
  // (a truncated PNG was published with exit status 0).
  TempDir dir;
  Invocation r;
  // 200 cells at 512^2 make a PNG of about 28 KB (the points about 8 KB).
  r.arguments = relax({"-n", "200", "-k", "1", "-o", dir.file("p.txt"), "--id-image", dir.file("cells.png"), "--resolution", "512"});
  r.file_size_bytes = 16 * 1024;
  Outcome o = run(r);
  expect_failure(o, dir.file("cells.png") + ": cannot write: File too large");
  EXPECT_EQ(entries(dir.path()), Names{});
  ASSERT_EQ(run(relax({"-o", dir.file("p.txt")})).exit_code, 0);
  r.arguments = {"analyze", "-i", dir.file("p.txt"), "-o", dir.file("an"), "--no-centroids"};
  o = run(r);
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_NE(o.err.find(": cannot write: File too large"), std::string::npos) << o.err;
  EXPECT_EQ(entries(dir.path()), Names{"p.txt"});
}

TEST(Outputs, TinyFileSystemWhenRoot) {
  TempDir dir;
  fs::create_directory(dir.file("small"));
  if (mount("bluetile-test", dir.file("small").c_str(), "tmpfs", 0, "size=100k") != 0)
    GTEST_SKIP() << "mounting a tmpfs needs root (CAP_SYS_ADMIN): full-disk outputs not tested here";
  struct Unmount {
    std::string path;
    ~Unmount() { umount2(path.c_str(), MNT_DETACH); }
  } unmount{dir.file("small")};
  // 2000 cells at 1024^2 make a PNG of about 230 KB.
  Outcome r = run(relax({"-n", "2000", "-k", "1", "-o", dir.file("small/p.txt"), "--id-image", dir.file("small/cells.png"),
                         "--resolution", "1024"}));
  expect_failure(r, dir.file("small/cells.png") + ": cannot write: No space left on device");
  EXPECT_EQ(entries(dir.file("small")), Names{});
  // Analysis of 300 points: about 140 KB of files.
  ASSERT_EQ(run(relax({"-n", "300", "-o", dir.file("p.txt")})).exit_code, 0);
  r = run({"analyze", "-i", dir.file("p.txt"), "-o", dir.file("small/an"), "--no-centroids"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write: No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(entries(dir.file("small")), Names{});
}

// Waits until `ready` holds, for at most 20 s.
template <typename Ready>
bool wait_until(Ready ready) {
  for (int i = 0; i < 2000; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(Outputs, InterruptsRemoveStagedFiles) {
  // SIGINT during a write left a 46 MB hidden temporary file. The run is held
  // mid-write deterministically: its point file goes to a FIFO nobody reads.
  for (int signal_number : {SIGINT, SIGTERM}) {
    TempDir dir;
    ASSERT_EQ(mkfifo(dir.file("pipe").c_str(), 0600), 0);
    Child child(Invocation{relax({"-n", "20000", "-k", "1", "--log", dir.file("log.csv"), "-o", dir.file("pipe")})});
    // Lets the tool open its end, then never reads; non-blocking so that a tool that failed
    // early cannot hang the test.
    int fd = open(dir.file("pipe").c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    // Blocked on a full pipe, with the log staged in a hidden folder beside its target.
    ASSERT_TRUE(wait_until([&] {
      int queued = 0;
      return ioctl(fd, FIONREAD, &queued) == 0 && queued >= 4096 && entries(dir.path()).size() > 1;
    }));
    EXPECT_NE(entries(dir.path())[0].find(".bluetile-"), std::string::npos);
    kill(child.pid(), signal_number);
    Outcome r = child.wait();
    close(fd);
    EXPECT_EQ(r.signal, signal_number) << r.err;
    EXPECT_EQ(entries(dir.path()), Names{"pipe|"});
  }
}

TEST(Outputs, AFolderMadeByAnotherRunMeanwhileIsNamedAndLeftAlone) {
  // Two runs into one new folder: the second to finish said "cannot create the folder:
  // Directory not empty". The run is held before its work by an input FIFO nobody writes yet,
  // while its folder is staged; then the folder appears with a file of another run's.
  TempDir dir;
  ASSERT_EQ(run(relax({"-o", dir.file("p.txt")})).exit_code, 0);
  ASSERT_EQ(mkfifo(dir.file("in.txt").c_str(), 0600), 0);
  Child child(Invocation{{"analyze", "-i", dir.file("in.txt"), "-o", dir.file("race"), "--no-psa-measures"}});
  ASSERT_TRUE(wait_until([&] { return entries(dir.path()).size() > 3; }));  // in.txt, p.txt and the staged folder
  fs::create_directory(dir.file("race"));
  dir.write("race/other.txt", "another run's\n");
  {
    std::ofstream feed(dir.file("in.txt"));
    feed << read_text(dir.file("p.txt"));
  }
  const Outcome r = child.wait();
  expect_failure(r, dir.file("race") + ": the folder was made by another process while this run worked; nothing was "
                                       "written to it (run again to write into it)");
  EXPECT_EQ(entries(dir.path()), (Names{"in.txt|", "p.txt", "race/", "race/other.txt"}));
  EXPECT_EQ(read_text(dir.file("race/other.txt")), "another run's\n");
}

TEST(Outputs, SignalsThatWereIgnoredStayIgnored) {
  // A script's background job (`cmd &`) inherits SIGINT ignored, and nohup SIGHUP: the watcher
  // took them over and a Ctrl-C meant for the script's foreground ended the job. Held mid-write
  // as above; SIGINT and SIGHUP change nothing, SIGTERM (not ignored) still ends it cleanly.
  TempDir dir;
  ASSERT_EQ(mkfifo(dir.file("pipe").c_str(), 0600), 0);
  Invocation ignoring{relax({"-n", "20000", "-k", "1", "--log", dir.file("log.csv"), "-o", dir.file("pipe")})};
  ignoring.wrapper = {"/bin/sh", "-c", "trap '' INT HUP; exec \"$0\" \"$@\""};
  Child child(ignoring);
  int fd = open(dir.file("pipe").c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(wait_until([&] {
    int queued = 0;
    return ioctl(fd, FIONREAD, &queued) == 0 && queued >= 4096 && entries(dir.path()).size() > 1;
  }));
  kill(child.pid(), SIGINT);
  kill(child.pid(), SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  siginfo_t ended{};  // WNOWAIT: looked at, left for child.wait() to collect
  ASSERT_EQ(waitid(P_PID, static_cast<id_t>(child.pid()), &ended, WEXITED | WNOHANG | WNOWAIT), 0);
  EXPECT_EQ(ended.si_pid, 0) << "a signal it inherited as ignored ended it (signal " << ended.si_status << ")";
  kill(child.pid(), SIGTERM);
  Outcome r = child.wait();
  close(fd);
  EXPECT_EQ(r.signal, SIGTERM) << r.err;
  EXPECT_EQ(entries(dir.path()), Names{"pipe|"});
}

TEST(Outputs, ImageMessagesNameTheUsersPath) {
  TempDir dir;
  // Image errors named the hidden temporary file.
  Outcome r = run(relax({"-o", dir.file("p.txt"), "--id-image", dir.file("cells.nosuchformat"), "--engine", "raster"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("bluetile: --id-image '" + dir.file("cells.nosuchformat") + "': this output writes ", 0), 0u)
      << r.err;
  EXPECT_EQ(r.err.find(".bluetile-"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  // ...and the plugin's load error was five lines; a wrong BLUETILE_OIIO_PLUGIN was ignored.
  Invocation bad_plugin{relax({"-o", dir.file("p.txt"), "--id-image", dir.file("cells.png"), "--engine", "raster"})};
  bad_plugin.environment = {{"BLUETILE_OIIO_PLUGIN", dir.file("missing.so")}};
  r = run(bad_plugin);
  expect_failure(r, "cannot load the image plugin named by BLUETILE_OIIO_PLUGIN: " + dir.file("missing.so") +
                        ": cannot open shared object file: No such file or directory");
  EXPECT_EQ(entries(dir.path()), Names{});
}

}  // namespace
}  // namespace bluetile::robustness
