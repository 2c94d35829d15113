// The tools' option validators: a value out of bounds is named with what was expected,
// in a few words (CLI11's own print the largest double in full).
#include <gtest/gtest.h>

#include <string>

#include "cli/tool.h"

namespace {

std::string verdict(const CLI::Validator& v, std::string input) { return v(input); }

TEST(CliValidators, PositiveAndNonNegativeNameTheValue) {
  EXPECT_EQ(verdict(bw::cli::kPositive, "0.5"), "");
  EXPECT_EQ(verdict(bw::cli::kPositive, "0"), "'0' must be a positive number");
  EXPECT_EQ(verdict(bw::cli::kPositive, "-1"), "'-1' must be a positive number");
  EXPECT_EQ(verdict(bw::cli::kPositive, "inf"), "'inf' must be a positive number");
  EXPECT_EQ(verdict(bw::cli::kPositive, "nan"), "'nan' must be a positive number");
  EXPECT_EQ(verdict(bw::cli::kPositive, "1x"), "'1x' is not a number");
  EXPECT_EQ(verdict(bw::cli::kNonNegative, "0"), "");
  EXPECT_EQ(verdict(bw::cli::kNonNegative, "-0.25"), "'-0.25' must be a number >= 0");
  EXPECT_EQ(verdict(bw::cli::kNonNegative, ""), "'' is not a number");
  EXPECT_EQ(verdict(bw::cli::kFinite, "-1e300"), "");
  EXPECT_EQ(verdict(bw::cli::kFinite, "nan"), "'nan' must be a finite number");
  EXPECT_EQ(verdict(bw::cli::kFinite, "-inf"), "'-inf' must be a finite number");
}

TEST(CliValidators, RangeIncludesItsBoundsAndPrintsThemShort) {
  const CLI::Validator unit = bw::cli::in_range(0, 1);
  EXPECT_EQ(verdict(unit, "0"), "");
  EXPECT_EQ(verdict(unit, "1"), "");
  EXPECT_EQ(verdict(unit, "1.0001"), "'1.0001' must be a number from 0 to 1");
  const CLI::Validator seeds = bw::cli::in_range(1, 1e6);
  EXPECT_EQ(verdict(seeds, "1e6"), "");
  EXPECT_EQ(verdict(seeds, "1e9"), "'1e9' must be a number from 1 to 1000000");
  EXPECT_EQ(verdict(bw::cli::in_range(0.001, 2.5), "3"), "'3' must be a number from 0.001 to 2.5");
}

}  // namespace
