// The helpers that put numbers into messages and summaries.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/text.h"
#include "test_support.h"

namespace {

TEST(Text, CountsReadAsPeopleWriteThem) {
  EXPECT_EQ(bw::human_count(12), "12");
  EXPECT_EQ(bw::human_count(730e3), "730 k");
  EXPECT_EQ(bw::human_count(1.25e6), "1.25 M");
  EXPECT_EQ(bw::human_count(84.5e9), "84.50 G");
  // Beyond any run (a refused sampling's estimate): the order, not "27000000.80 G".
  EXPECT_EQ(bw::human_count(2.7e16), "2.7e+16");
}

TEST(Text, BytesAndDurations) {
  EXPECT_EQ(bw::human_bytes(512), "512 B");
  EXPECT_EQ(bw::human_bytes(3 * 1024 + 200), "3.2 KiB");
  EXPECT_EQ(bw::human_bytes(3ull << 60), "3.0 EiB");
  EXPECT_EQ(bw::human_duration(12.34), "12.3 s");
  EXPECT_EQ(bw::human_duration(245), "4 min 05 s");
  EXPECT_EQ(bw::human_duration(7380), "2 h 03 min");
  EXPECT_EQ(bw::human_duration(NAN), "?");
}

TEST(Text, SplitKeepsEmptyPieces) {
  EXPECT_EQ(bw::split("a::b", ':'), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(bw::split("", ':'), (std::vector<std::string>{""}));
}

// What a user gives for a scene by mistake is named: a folder, a missing file, a run
// file (HDF5) or another binary file.
TEST(Text, ReadTextFileNamesWhatItGot) {
  bw::test::TempDir dir;
  std::ofstream(dir.file("scene.toml")) << "spacing = 0.02\n";
  EXPECT_EQ(bw::read_text_file(dir.file("scene.toml"), "a scene file"), "spacing = 0.02\n");
  const auto error = [&](const std::string& path) {
    try {
      bw::read_text_file(path, "a scene file");
    } catch (const bw::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error(dir.file("none.toml")), dir.file("none.toml") + ": no such file");
  EXPECT_EQ(error(dir.path()), dir.path() + ": is a folder, not a scene file");
  std::ofstream(dir.file("run.h5"), std::ios::binary) << std::string("\x89HDF\r\n\x1a\n\0\0\0", 11);
  EXPECT_EQ(error(dir.file("run.h5")), dir.file("run.h5") + ": is an HDF5 file, not a scene file");
  std::ofstream(dir.file("mesh.stl"), std::ios::binary) << std::string("solid\0\x01\x02", 8);
  EXPECT_EQ(error(dir.file("mesh.stl")), dir.file("mesh.stl") + ": is a binary file, not a scene file");
}

}  // namespace
