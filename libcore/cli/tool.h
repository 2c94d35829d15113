// The frame every tool's main() sits in: parse the command line with CLI11, run the
// body, catch once, map the failure to an exit code (common/error.h).
//
//   int main(int argc, char** argv) {
//     CLI::App app{"Sample a triangle mesh into particles", "bw-sample"};
//     Options o;  ... app.add_option(...) ...
//     return bw::cli::run(app, argc, argv, [&] { ...; return bw::kExitOk; });
//   }
//
// Errors print one line on stderr, "bw-sample: <message>"; CLI11's own usage errors
// exit with 2 like every other bad input.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.h"

namespace bw::cli {

// Adds --version, the footer with example command lines, and consistent formatting.
void setup(CLI::App& app, const std::string& examples);

int run(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

// Prints "tool: message" on stderr (for warnings and notes from tools).
void note(const CLI::App& app, const std::string& message);

// CLI11 validators whose errors name the value and what was expected in a few words
// (CLI11's own print their bounds to six decimals, the largest double in full).
extern const CLI::Validator kFinite;       // a finite number (CLI11 takes nan and inf)
extern const CLI::Validator kPositive;     // a finite number > 0
extern const CLI::Validator kNonNegative;  // a finite number >= 0
CLI::Validator in_range(double lo, double hi);  // a finite number from lo to hi

}  // namespace bw::cli
