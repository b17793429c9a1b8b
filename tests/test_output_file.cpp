// Output files (core/output_file.h): what each kind of path gets, all-or-none publication,
// refusals before any work, streaming. Special files are made in a temporary folder.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "test_support.h"

namespace bluetile {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::TempDir;

// The message of the Error that f throws, or "" when it throws none.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(lstat(path.c_str(), &st), 0) << path;
  return st.st_mode;
}

// Everything in `folder`, hidden entries and subfolders included, relative and sorted.
std::vector<std::string> everything_in(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    names.push_back(entry.path().lexically_relative(folder).string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(OutputFile, NewAndReplacedRegularFilesKeepThePermissionBits) {
  TempDir dir;
  write_output(dir.file("new.txt"), "fresh\n");
  EXPECT_EQ(read_text(dir.file("new.txt")), "fresh\n");
  const mode_t umask_now = umask(0);
  umask(umask_now);
  EXPECT_EQ(mode_of(dir.file("new.txt")) & 0777, 0666 & ~umask_now);

  // A 0600 file once came back 0644.
  dir.write("secret.txt", "old\n");
  chmod(dir.file("secret.txt").c_str(), 0600);
  write_output(dir.file("secret.txt"), "new\n");
  EXPECT_EQ(read_text(dir.file("secret.txt")), "new\n");
  EXPECT_EQ(mode_of(dir.file("secret.txt")) & 07777, 0600u);
  chmod(dir.file("secret.txt").c_str(), 0751);
  write_output(dir.file("secret.txt"), "newer\n");
  EXPECT_EQ(mode_of(dir.file("secret.txt")) & 07777, 0751u);
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"new.txt", "secret.txt"}));
}

TEST(OutputFile, SymbolicLinksAreFollowedAndStayLinks) {
  TempDir dir;
  fs::create_directory(dir.file("elsewhere"));
  dir.write("elsewhere/target.txt", "old\n");
  chmod(dir.file("elsewhere/target.txt").c_str(), 0640);
  fs::create_symlink("elsewhere/target.txt", dir.file("link.txt"));
  fs::create_symlink("link.txt", dir.file("link-to-link.txt"));
  write_output(dir.file("link-to-link.txt"), "through two links\n");
  EXPECT_TRUE(S_ISLNK(mode_of(dir.file("link.txt"))));
  EXPECT_TRUE(S_ISLNK(mode_of(dir.file("link-to-link.txt"))));
  EXPECT_EQ(read_text(dir.file("elsewhere/target.txt")), "through two links\n");
  EXPECT_EQ(mode_of(dir.file("elsewhere/target.txt")) & 0777, 0640u);
  // A dangling link creates the file it names.
  fs::create_symlink("elsewhere/created.txt", dir.file("dangling.txt"));
  write_output(dir.file("dangling.txt"), "made\n");
  EXPECT_EQ(read_text(dir.file("elsewhere/created.txt")), "made\n");
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"dangling.txt", "elsewhere", "elsewhere/created.txt",
                                                                 "elsewhere/target.txt", "link-to-link.txt", "link.txt"}));
  // A loop is an error, not a hang.
  fs::create_symlink("loop-b", dir.file("loop-a"));
  fs::create_symlink("loop-a", dir.file("loop-b"));
  EXPECT_NE(error_of([&] { write_output(dir.file("loop-a"), "x"); }).find("loop-a: cannot write: Too many levels of symbolic links"),
            std::string::npos);
}

TEST(OutputFile, FifoIsWrittenDirectlyAndStaysAFifo) {
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_text(fifo); });
  std::string big(300000, 'x');  // more than a pipe holds: the writer must stream
  write_output(fifo, big);
  reader.join();
  EXPECT_EQ(received, big);
  EXPECT_TRUE(S_ISFIFO(mode_of(fifo)));
  EXPECT_EQ(everything_in(dir.path()), std::vector<std::string>{"pipe"});
}

TEST(OutputFile, DeviceNodesAreWrittenDirectly) {
  TempDir dir;
  const std::string null_device = dir.file("mynull"), full_device = dir.file("myfull");
  if (mknod(null_device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0 ||
      mknod(full_device.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) {
    GTEST_SKIP() << "mknod is not permitted here (needs CAP_MKNOD): device outputs not tested";
  }
  write_output(null_device, "into the void\n");
  EXPECT_TRUE(S_ISCHR(mode_of(null_device)));  // it became a regular file
  EXPECT_EQ(error_of([&] { write_output(full_device, "x"); }), full_device + ": cannot write: No space left on device");
  EXPECT_TRUE(S_ISCHR(mode_of(full_device)));
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"myfull", "mynull"}));
}

TEST(OutputFile, DescriptorPathsWriteThatDescriptor) {
  TempDir dir;
  int fd = open(dir.file("shell-redirect.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  write_output("/dev/fd/" + std::to_string(fd), "via the descriptor\n");
  write_output("/proc/self/fd/" + std::to_string(fd), "and again\n");
  close(fd);
  EXPECT_EQ(read_text(dir.file("shell-redirect.txt")), "via the descriptor\nand again\n");
  EXPECT_EQ(everything_in(dir.path()), std::vector<std::string>{"shell-redirect.txt"});
  EXPECT_NE(error_of([] { write_output("-", "x"); }).find("cannot be standard output"), std::string::npos);
}

TEST(OutputFile, StandardOutputIsKnownAsSuch) {
  // "-" is kept as a copy of descriptor 1, and is_stdout() tested for 1 itself.
  // One set each: where standard output is a file, "-" and /dev/stdout are the same output.
  TempDir dir;
  EXPECT_TRUE(OutputSet().add("-", {.allow_stdout = true}).is_stdout());
  EXPECT_TRUE(OutputSet().add("/dev/stdout").is_stdout());
  EXPECT_FALSE(OutputSet().add(dir.file("p.txt")).is_stdout());
  EXPECT_FALSE(OutputSet().add("/dev/stderr").is_stdout());
}

TEST(OutputFile, RefusedBeforeAnyWork) {
  TempDir dir;
  fs::create_directory(dir.file("folder"));
  dir.write("input.txt", "0.5 0.5\n");
  fs::create_symlink("input.txt", dir.file("input-link.txt"));
  fs::create_hard_link(dir.file("input.txt"), dir.file("input-hard.txt"));

  auto refused = [&](const std::function<void(OutputSet&)>& declare) {
    OutputSet outputs;
    outputs.add_input(dir.file("input.txt"));
    return error_of([&] { declare(outputs); });
  };
  EXPECT_EQ(refused([&](OutputSet& o) { o.add(dir.file("folder")); }), dir.file("folder") + ": is a folder");
  EXPECT_EQ(refused([&](OutputSet& o) { o.add(dir.file("no/such/x.txt")); }),
            dir.file("no/such/x.txt") + ": folder '" + dir.file("no/such") + "' does not exist");
  // --log pointed at the input replaced the input.
  for (const char* same : {"input.txt", "input-link.txt", "input-hard.txt", "folder/../input.txt"}) {
    EXPECT_EQ(refused([&](OutputSet& o) { o.add(dir.file(same)); }),
              dir.file(same) + ": is the same file as the input " + dir.file("input.txt"));
  }
  EXPECT_EQ(refused([&](OutputSet& o) {
              o.add(dir.file("out.txt"));
              o.add(dir.path() + "/folder/../out.txt");
            }),
            dir.path() + "/folder/../out.txt: is the same file as the output " + dir.file("out.txt"));
  if (geteuid() != 0) {  // root may write anywhere
    chmod(dir.file("folder").c_str(), 0555);
    EXPECT_EQ(refused([&](OutputSet& o) { o.add(dir.file("folder/x.txt")); }),
              dir.file("folder/x.txt") + ": cannot write in folder '" + dir.file("folder") + "': Permission denied");
    chmod(dir.file("folder").c_str(), 0755);
    dir.write("locked.txt", "keep\n");
    chmod(dir.file("locked.txt").c_str(), 0444);
    EXPECT_EQ(refused([&](OutputSet& o) { o.add(dir.file("locked.txt")); }),
              dir.file("locked.txt") + ": cannot replace: Permission denied");
  }
  // Nothing staged is left after a refusal.
  std::vector<std::string> expected = {"folder", "input-hard.txt", "input-link.txt", "input.txt"};
  if (geteuid() != 0) expected.insert(expected.begin() + 3, "locked.txt");
  EXPECT_EQ(everything_in(dir.path()), expected);
  EXPECT_EQ(read_text(dir.file("input.txt")), "0.5 0.5\n");
}

TEST(OutputFile, AllOrNone) {
  TempDir dir;
  dir.write("a.txt", "old a\n");
  {
    OutputSet outputs;
    outputs.add(dir.file("a.txt")).write("new a\n");
    outputs.add(dir.file("b.txt")).write("new b\n");
    OutputFile& c = outputs.add(dir.file("c.txt"));
    EXPECT_THROW(c.write([](OutputStream& out) {
      out.write("half");
      throw Error("the writer failed");
    }),
                 Error);
    // Destroyed unpublished: nothing appears, the old file stays.
  }
  EXPECT_EQ(everything_in(dir.path()), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(read_text(dir.file("a.txt")), "old a\n");

  // A rename that fails at publish puts the earlier ones back.
  {
    OutputSet outputs;
    outputs.add(dir.file("a.txt")).write("new a\n");
    outputs.add(dir.file("b.txt")).write("new b\n");
    fs::create_directory(dir.file("b.txt"));
    dir.write("b.txt/occupied", "");
    EXPECT_NE(error_of([&] { outputs.publish(); }).find(dir.file("b.txt") + ": cannot replace:"), std::string::npos);
  }
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"a.txt", "b.txt", "b.txt/occupied"}));
  EXPECT_EQ(read_text(dir.file("a.txt")), "old a\n");
}

TEST(OutputFile, MissingFolderAppearsWholeAtPublish) {
  TempDir dir;
  const std::string folder = dir.file("deep/er/analysis");
  {
    OutputSet outputs;
    outputs.add_folder(folder);
    outputs.add(folder + "/one.txt").write("1\n");
    outputs.add(folder + "/two.txt").write("2\n");
    EXPECT_FALSE(fs::exists(dir.file("deep")));
  }  // not published
  EXPECT_EQ(everything_in(dir.path()), std::vector<std::string>{});
  OutputSet outputs;
  outputs.add_folder(folder + "/");
  outputs.add(folder + "/one.txt").write("1\n");
  outputs.add(folder + "/two.txt").write("2\n");
  outputs.publish();
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"deep", "deep/er", "deep/er/analysis",
                                                                 "deep/er/analysis/one.txt", "deep/er/analysis/two.txt"}));
}

// A folder used again keeps the files of an earlier run that this one does not write (another
// run's options wrote more): nothing of them is removed, and one line says which they are.
TEST(OutputFile, ReusedFolderNamesTheFilesThisRunDidNotWrite) {
  TempDir dir;
  const std::string folder = dir.file("analysis");
  auto publish = [&](const std::string& path, const std::vector<std::string>& names) {
    testing::internal::CaptureStderr();
    OutputSet outputs;
    outputs.add_folder(path);
    for (const std::string& name : names) outputs.add(folder + "/" + name).write(name + "\n");
    outputs.publish();
    return testing::internal::GetCapturedStderr();
  };
  EXPECT_EQ(publish(folder, {"a.txt", "b.png", "c.csv"}), "");  // new: nothing to say
  EXPECT_EQ(publish(folder, {"a.txt", "b.png", "c.csv"}), "");  // the same files again
  dir.write("analysis/.hidden", "mine\n");                     // hidden files and folders are no outputs
  fs::create_directory(dir.file("analysis/sub"));
  EXPECT_EQ(publish(folder + "/", {"a.txt"}),
            "bluetile: note: " + folder + "/ also holds 2 files this run did not write, left as they are: b.png, c.csv\n");
  EXPECT_EQ(read_text(dir.file("analysis/b.png")), "b.png\n");  // kept
  for (const char* name : {"d", "e", "f", "g"}) dir.write(std::string("analysis/") + name, "\n");
  EXPECT_EQ(publish(folder, {"e"}),
            "bluetile: note: " + folder +
                " also holds 6 files this run did not write, left as they are: a.txt, b.png, c.csv, d and 2 more\n");
  EXPECT_EQ(publish(folder, {"a.txt", "b.png", "c.csv", "d", "e", "f"}),
            "bluetile: note: " + folder + " also holds 1 file this run did not write, left as it is: g\n");
}

TEST(OutputFile, StreamsAndReportsEveryFailedWrite) {
  TempDir dir;
  // A point file far larger than the stream's buffer, written point by point.
  PointSet set;
  set.points = test::uniform_points(20000, 5);
  write_point_file(dir.file("p.txt"), set);
  EXPECT_EQ(read_point_file(dir.file("p.txt")).points, set.points);
  // A reader that goes away: the error names the user's path, not a temporary one.
  auto previous = std::signal(SIGPIPE, SIG_IGN);
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread reader([&] {
    int fd = open(fifo.c_str(), O_RDONLY);
    char byte;
    EXPECT_EQ(read(fd, &byte, 1), 1);
    close(fd);
  });
  std::string message = error_of([&] { write_point_file(fifo, set); });
  reader.join();
  std::signal(SIGPIPE, previous);
  EXPECT_EQ(message, fifo + ": cannot write: Broken pipe");
  // ostream() forwards to the same checked stream.
  write_output(dir.file("o.txt"), [](OutputStream& out) {
    out.ostream() << "x=" << 42 << '\n';
    out.print("%.3f\n", 0.5);
  });
  EXPECT_EQ(read_text(dir.file("o.txt")), "x=42\n0.500\n");
  EXPECT_EQ(everything_in(dir.path()), (std::vector<std::string>{"o.txt", "p.txt", "pipe"}));
}

}  // namespace
}  // namespace bluetile
