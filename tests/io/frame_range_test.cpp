// The frame files of a folder, as bw-render, bw-export and bw-measure take them, and
// the one-line errors for what users give instead.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.h"
#include "io/frame_range.h"
#include "test_support.h"

namespace {

using bw::test::TempDir;

void touch(const std::string& path) { std::ofstream(path) << "x"; }

// The message of the InputError that `f` throws; empty when it throws none.
template <class F>
std::string input_error(F f) {
  try {
    f();
  } catch (const bw::InputError& e) {
    return e.what();
  }
  return {};
}

TEST(FrameFiles, ListsNumberedFilesInFrameOrderAndNothingElse) {
  TempDir dir;
  for (const char* name : {"000010.h5", "000002.h5", "000001.h5", "run.h5", "000003.h5.tmp", "12a.h5", "000004.txt"})
    touch(dir.file(name));
  std::filesystem::create_directory(dir.file("000005.h5"));  // a folder is no frame
  const auto frames = bw::frame_files(dir.path());
  ASSERT_EQ(frames.size(), 3u);
  auto it = frames.begin();
  EXPECT_EQ(it->first, 1);
  EXPECT_EQ(it->second, dir.file("000001.h5"));
  EXPECT_EQ((++it)->first, 2);
  EXPECT_EQ((++it)->first, 10);
}

TEST(FrameFiles, NameWhatWasGivenInsteadOfAFolderOfFrames) {
  TempDir dir;
  EXPECT_EQ(input_error([&] { bw::frame_files(dir.file("nowhere")); }),
            dir.file("nowhere") + ": no such folder of frames");
  touch(dir.file("run.h5"));
  EXPECT_EQ(input_error([&] { bw::frame_files(dir.file("run.h5")); }),
            dir.file("run.h5") + ": is a file, not a folder of frames (bw-sim's OUTDIR/frames)");
  EXPECT_TRUE(bw::frame_files(dir.path()).empty());
  EXPECT_EQ(input_error([&] { bw::require_frame_files(dir.path()); }),
            dir.path() + ": holds no frame files (NNNNNN.h5)");
}

TEST(FrameFiles, ARunFolderGivenForItsFramesIsPointedToThem) {
  TempDir dir;
  std::filesystem::create_directory(dir.file("frames"));
  touch(dir.file("run.h5"));
  // An empty frames folder is not the fix: the plain message.
  EXPECT_EQ(input_error([&] { bw::require_frame_files(dir.path()); }),
            dir.path() + ": holds no frame files (NNNNNN.h5)");
  touch(dir.file("frames/000000.h5"));
  EXPECT_EQ(input_error([&] { bw::require_frame_files(dir.path()); }),
            dir.path() + ": holds no frame files (NNNNNN.h5); its frames folder does: give " + dir.file("frames"));
  EXPECT_EQ(bw::require_frame_files(dir.file("frames")).size(), 1u);
}

}  // namespace
