// Writing through a temporary file: links are written through, and devices and pipes
// (/dev/null, a FIFO) get the bytes copied in, never a regular file in their place.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "common/error.h"
#include "io/h5.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using bw::test::TempDir;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Reads a FIFO to its end on another thread. Should the writer fail before it opens
// the FIFO, the destructor opens it once to unblock the reader, so a failing test
// ends instead of hanging.
class FifoReader {
 public:
  explicit FifoReader(std::string path)
      : path_(std::move(path)), bytes_(std::async(std::launch::async, [p = path_] { return slurp(p); })) {}
  ~FifoReader() {
    if (!bytes_.valid()) return;
    const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    bytes_.wait();
  }
  std::string get() { return bytes_.get(); }

 private:
  std::string path_;
  std::future<std::string> bytes_;
};

TEST(AtomicFile, ReplacesAFileAndLeavesNoTemporary) {
  TempDir dir;
  std::ofstream(dir.file("a.txt")) << "old";
  bw::write_file_atomically(dir.file("a.txt"), "new", 3);
  EXPECT_EQ(slurp(dir.file("a.txt")), "new");
  EXPECT_EQ(bw::test::list_folder(dir.path()), "a.txt");
}

// A link named as the output keeps pointing where it did, at the new bytes.
TEST(AtomicFile, WritesThroughALink) {
  TempDir dir;
  fs::create_directories(dir.file("data"));
  std::ofstream(dir.file("data/run.h5")) << "old";
  fs::create_symlink("data/run.h5", dir.file("latest.h5"));
  bw::write_file_atomically(dir.file("latest.h5"), "new", 3);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir.file("latest.h5"))));
  EXPECT_EQ(slurp(dir.file("data/run.h5")), "new");
  EXPECT_EQ(bw::test::list_folder(dir.path()), "data latest.h5");
  EXPECT_EQ(bw::test::list_folder(dir.file("data")), "run.h5");
}

// A pipe takes the finished bytes and stays a pipe (a rename over /dev/null as root
// would have put a regular file in its place); its temporary file is gone.
TEST(AtomicFile, CopiesIntoAPipe) {
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  FifoReader reader(fifo);
  std::string temp;
  {
    bw::AtomicFile file(fifo);
    temp = file.temp_path();
    EXPECT_NE(fs::path(temp).parent_path(), fs::path(dir.path()));
    std::ofstream(temp, std::ios::binary) << "finished bytes";
    file.commit();
  }
  EXPECT_EQ(reader.get(), "finished bytes");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_EQ(bw::test::list_folder(dir.path()), "pipe");
}

TEST(AtomicFile, AnHdf5FileIntoAPipeReadsBack) {
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  FifoReader reader(fifo);
  {
    bw::h5::File file = bw::h5::File::create(fifo, "test");
    file.root().set_attr("answer", 42.0);
    file.commit();
  }
  std::ofstream(dir.file("copy.h5"), std::ios::binary) << reader.get();
  const bw::h5::File copy = bw::h5::File::open(dir.file("copy.h5"), "test");
  EXPECT_EQ(copy.root().attr<double>("answer"), 42.0);
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(AtomicFile, UncommittedWriteToAPipeLeavesNothing) {
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string temp;
  {
    bw::AtomicFile file(fifo);
    temp = file.temp_path();
    std::ofstream(temp, std::ios::binary) << "half";
  }
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(AtomicFile, ADeviceThatCannotBeWrittenIsBadInput) {
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0400), 0);
  if (::access(fifo.c_str(), W_OK) == 0) GTEST_SKIP() << "running as root: every file is writable";
  EXPECT_THROW(bw::check_output_file(fifo), bw::InputError);
}

// Stopped by a signal with a file half written, a tool leaves no temporary file: the
// child writes one, then SIGTERM ends it as it would any tool, by the signal.
TEST(AtomicFile, ASignalRemovesTheTemporaryFile) {
  TempDir dir;
  for (int signal : {SIGTERM, SIGINT, SIGHUP}) {
    std::fflush(nullptr);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      bw::AtomicFile file(dir.file("out.h5"));
      std::ofstream(file.temp_path(), std::ios::binary) << "half";
      ::raise(signal);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "status " << status;
    EXPECT_EQ(bw::test::list_folder(dir.path()), "") << "signal " << signal;
  }
}

}  // namespace
