// write_file_atomic and read_file on what is not a plain file: symbolic links (live and
// dangling), FIFOs, character devices, standard input and output, existing files' modes and
// failed writes. Run under ASan/UBSan in CI (label unit).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "tessera/io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace tessera;
using namespace tessera::io;  // NOLINT(google-build-using-namespace): the tests of io's file writes

namespace {

std::vector<std::uint8_t> bytes_of(const std::string& text) {
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Names in `dir` other than `keep`: stray temporaries show up here.
std::vector<std::string> others(const fs::path& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (std::find(keep.begin(), keep.end(), name) == keep.end()) out.push_back(name);
  }
  return out;
}

}  // namespace

TEST(SafeWrite, SymlinkIsWrittenThroughAndStaysALink) {
  const fs::path dir = test::temp_dir("safe_write_link");
  fs::create_directories(dir / "real");
  std::ofstream(dir / "real" / "target.bin") << "old";
  fs::create_symlink("real/target.bin", dir / "link.bin");
  ASSERT_TRUE(write_file_atomic((dir / "link.bin").string(), bytes_of("new")).ok());
  EXPECT_TRUE(fs::is_symlink(dir / "link.bin"));
  EXPECT_EQ(fs::read_symlink(dir / "link.bin"), fs::path("real/target.bin"));
  EXPECT_EQ(slurp(dir / "real" / "target.bin"), "new");
  EXPECT_TRUE(others(dir / "real", {"target.bin"}).empty());
  EXPECT_TRUE(others(dir, {"real", "link.bin"}).empty());
}

TEST(SafeWrite, ChainOfLinksReachesTheFinalTarget) {
  const fs::path dir = test::temp_dir("safe_write_chain");
  std::ofstream(dir / "target") << "old";
  fs::create_symlink("target", dir / "a");
  fs::create_symlink(dir / "a", dir / "b");  // absolute link to a relative link
  ASSERT_TRUE(write_file_atomic((dir / "b").string(), bytes_of("chain")).ok());
  EXPECT_TRUE(fs::is_symlink(dir / "a"));
  EXPECT_TRUE(fs::is_symlink(dir / "b"));
  EXPECT_EQ(slurp(dir / "target"), "chain");
}

TEST(SafeWrite, DanglingLinkGetsItsTargetCreated) {
  const fs::path dir = test::temp_dir("safe_write_dangling");
  fs::create_directories(dir / "sub");
  fs::create_symlink("sub/new.bin", dir / "dangling");
  ASSERT_TRUE(write_file_atomic((dir / "dangling").string(), bytes_of("made")).ok());
  EXPECT_TRUE(fs::is_symlink(dir / "dangling"));
  EXPECT_EQ(slurp(dir / "sub" / "new.bin"), "made");
  // A link into a folder that does not exist fails, names the link, and changes nothing.
  fs::create_symlink("nowhere/x.bin", dir / "broken");
  const Status s = write_file_atomic((dir / "broken").string(), bytes_of("x"));
  EXPECT_EQ(s.code, ErrorCode::io_error);
  EXPECT_NE(s.message.find("broken"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("No such file"), std::string::npos) << s.message;
  EXPECT_TRUE(fs::is_symlink(dir / "broken"));
}

TEST(SafeWrite, LinkLoopIsAnError) {
  const fs::path dir = test::temp_dir("safe_write_loop");
  fs::create_symlink("b", dir / "a");
  fs::create_symlink("a", dir / "b");
  const Status s = write_file_atomic((dir / "a").string(), bytes_of("x"));
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("symbolic links"), std::string::npos) << s.message;
  EXPECT_TRUE(fs::is_symlink(dir / "a"));
}

TEST(SafeWrite, DevNullIsWrittenNotReplaced) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  ASSERT_TRUE(write_file_atomic("/dev/null", bytes_of("discarded")).ok());
  struct stat after {};
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(before.st_rdev, after.st_rdev);
}

TEST(SafeWrite, FifoWithAReaderGetsTheBytes) {
  const fs::path dir = test::temp_dir("safe_write_fifo");
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = slurp(fifo); });
  const std::string payload(200000, 'p');  // more than a pipe buffer
  const Status s = write_file_atomic(fifo.string(), bytes_of(payload));
  reader.join();
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(received, payload);
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(others(dir, {"pipe"}).empty());
}

TEST(SafeWrite, ExistingFileKeepsItsPermissionBits) {
  const fs::path dir = test::temp_dir("safe_write_mode");
  const fs::path p = dir / "keep.bin";
  std::ofstream(p) << "old";
  ASSERT_EQ(::chmod(p.c_str(), 0640), 0);
  ASSERT_TRUE(write_file_atomic(p.string(), bytes_of("new")).ok());
  struct stat st {};
  ASSERT_EQ(::stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_EQ(slurp(p), "new");
  // A new file gets 0666 less the umask.
  const mode_t mask = ::umask(022);
  ::umask(mask);
  ASSERT_TRUE(write_file_atomic((dir / "fresh.bin").string(), bytes_of("x")).ok());
  ASSERT_EQ(::stat((dir / "fresh.bin").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0666u & ~mask);
}

TEST(SafeWrite, DirectoryIsAnErrorThatNamesIt) {
  const fs::path dir = test::temp_dir("safe_write_dir");
  fs::create_directories(dir / "folder.png");
  const Status s = write_file_atomic((dir / "folder.png").string(), bytes_of("x"));
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("folder.png: is a directory"), std::string::npos) << s.message;
  EXPECT_TRUE(others(dir, {"folder.png"}).empty());
}

TEST(SafeWrite, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  // A file system that is full: /dev/full refuses every write with ENOSPC. A link to it is
  // written in place (a device), and the failure is reported.
  const fs::path dir = test::temp_dir("safe_write_full");
  const Status s = write_file_atomic("/dev/full", bytes_of("x"));
  EXPECT_EQ(s.code, ErrorCode::io_error);
  EXPECT_NE(s.message.find("/dev/full"), std::string::npos) << s.message;
  // A read-only folder (skipped as root, who writes anywhere): the old file survives.
  if (::geteuid() != 0) {
    std::ofstream(dir / "old.bin") << "old";
    ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
    const Status r = write_file_atomic((dir / "old.bin").string(), bytes_of("new"));
    ::chmod(dir.c_str(), 0755);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.message.find("Permission denied"), std::string::npos) << r.message;
    EXPECT_EQ(slurp(dir / "old.bin"), "old");
    EXPECT_TRUE(others(dir, {"old.bin"}).empty());
  }
}

TEST(SafeWrite, DashWritesStandardOutput) {
  // Run in a child whose stdout is a pipe: "-" must reach the pipe byte for byte.
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    ::close(fds[0]);
    ::close(fds[1]);
    const Status s = write_file_atomic("-", bytes_of("to stdout\n"));
    ::_exit(s.ok() ? 0 : 3);
  }
  ::close(fds[1]);
  std::string got;
  char buf[256];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) got.append(buf, std::size_t(n));
  ::close(fds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(got, "to stdout\n");
}

TEST(StreamRead, PipesAndFifosAreReadToTheirEnd) {
  const fs::path dir = test::temp_dir("stream_read");
  const fs::path fifo = dir / "in";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string payload(300000, 'q');
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << payload; });
  Result<std::vector<std::uint8_t>> got = read_file(fifo.string());
  writer.join();
  ASSERT_TRUE(got.ok()) << got.status().message;
  EXPECT_EQ(std::string(got->begin(), got->end()), payload);
}

TEST(StreamRead, LimitHoldsForStreams) {
  const fs::path dir = test::temp_dir("stream_limit");
  const fs::path fifo = dir / "in";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // The reader closes the FIFO early: the writer must see EPIPE, not die of SIGPIPE.
  struct sigaction ignore {
  }, old{};
  ignore.sa_handler = SIG_IGN;
  ASSERT_EQ(::sigaction(SIGPIPE, &ignore, &old), 0);
  std::thread writer([&] {
    // The reader stops early; the writer then gets EPIPE, which an ofstream absorbs.
    std::ofstream out(fifo, std::ios::binary);
    const std::string chunk(65536, 'z');
    for (int i = 0; i < 8 && out; ++i) out << chunk << std::flush;
  });
  Result<std::vector<std::uint8_t>> got = read_file(fifo.string(), 100000);
  EXPECT_EQ(got.status().code, ErrorCode::too_large);
  EXPECT_NE(got.status().message.find("limit of 100000 bytes"), std::string::npos);
  // The writer still had data (512 KiB against a 64 KiB pipe buffer): its next write fails
  // with EPIPE once the reader closed, and it stops.
  writer.join();
  ::sigaction(SIGPIPE, &old, nullptr);
}

TEST(StreamRead, DirectoryAndMissingFileGiveTheOsReason) {
  const fs::path dir = test::temp_dir("stream_errors");
  Result<std::vector<std::uint8_t>> d = read_file(dir.string());
  EXPECT_NE(d.status().message.find("is a directory"), std::string::npos);
  Result<std::vector<std::uint8_t>> m = read_file((dir / "nope").string());
  EXPECT_NE(m.status().message.find("nope: cannot open: No such file or directory"),
            std::string::npos)
      << m.status().message;
}

TEST(ImageOutput, FormatFollowsTheExtensionOrIsRefused) {
  EXPECT_EQ(*image_format_for_output("a.png"), ImageFormat::png);
  EXPECT_EQ(*image_format_for_output("A.JPG"), ImageFormat::jpeg);
  EXPECT_EQ(*image_format_for_output("x.jpeg"), ImageFormat::jpeg);
  EXPECT_EQ(*image_format_for_output("x.bmp"), ImageFormat::bmp);
  EXPECT_EQ(*image_format_for_output("x.tga"), ImageFormat::tga);
  EXPECT_EQ(*image_format_for_output("-"), ImageFormat::png);
  EXPECT_EQ(*image_format_for_output("dir.d/noext"), ImageFormat::png);
  Result<ImageFormat> gif = image_format_for_output("x.gif");
  ASSERT_FALSE(gif.ok());
  EXPECT_NE(gif.status().message.find("x.gif: cannot write '.gif' images"), std::string::npos);

  ImageRGBA8 img(5, 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = std::uint8_t(i * 7);
  img.has_alpha = true;
  const fs::path dir = test::temp_dir("image_output");
  for (const char* name : {"o.png", "o.bmp", "o.tga", "o.jpg"}) {
    const std::string p = (dir / name).string();
    ASSERT_TRUE(write_image(p, img).ok()) << name;
    Result<std::vector<std::uint8_t>> bytes = read_file(p);
    ASSERT_TRUE(bytes.ok());
    const ImageFormat want = *image_format_for_output(p);
    EXPECT_EQ(detect_image_format(*bytes), want) << name;
    Result<ImageRGBA8> back = decode_image(*bytes, p);
    ASSERT_TRUE(back.ok()) << back.status().message;
    EXPECT_EQ(back->width, 5);
    EXPECT_EQ(back->height, 3);
    if (want != ImageFormat::jpeg) {
      EXPECT_EQ(back->pixels, img.pixels) << name;  // lossless
    }
  }
}
