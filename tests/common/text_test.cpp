// The helpers that put numbers into messages and summaries.
#include <gtest/gtest.h>

#include <cmath>

#include "common/text.h"

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

}  // namespace
