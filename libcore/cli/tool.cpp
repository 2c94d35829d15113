#include "cli/tool.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <new>
#include <string>

#include <fmt/format.h>

namespace bw::cli {

namespace {

// The number `input` holds, or an error that names it; then `accept` decides.
CLI::Validator number_check(std::function<bool(double)> accept, std::string expected, const std::string& name) {
  return CLI::Validator(
      [accept = std::move(accept), expected = std::move(expected)](std::string& input) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(input.c_str(), &end);
        if (end == input.c_str() || *end != '\0') return "'" + input + "' is not a number";
        if (!std::isfinite(value) || !accept(value)) return "'" + input + "' must be " + expected;
        return {};
      },
      name, name);
}

std::string shortest(double v) { return fmt::format("{}", v); }

}  // namespace

const CLI::Validator kFinite = number_check([](double) { return true; }, "a finite number", "FINITE");
const CLI::Validator kPositive = number_check([](double v) { return v > 0; }, "a positive number", "POSITIVE");
const CLI::Validator kNonNegative =
    number_check([](double v) { return v >= 0; }, "a number >= 0", "NONNEGATIVE");

CLI::Validator in_range(double lo, double hi) {
  const std::string from = shortest(lo), to = shortest(hi);
  return number_check([lo, hi](double v) { return v >= lo && v <= hi; }, "a number from " + from + " to " + to,
                      "[" + from + " - " + to + "]");
}

void setup(CLI::App& app, const std::string& examples) {
  app.set_version_flag("--version", std::string(app.get_name()) + " " BW_VERSION);
  if (!examples.empty()) app.footer("Examples:\n" + examples);
  app.get_formatter()->column_width(34);
}

void note(const CLI::App& app, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", app.get_name().c_str(), message.c_str());
}

int run(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  const std::string name = app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "%s: %s (see %s --help)\n", name.c_str(), what.c_str(), name.c_str());
    return kExitBadInput;
  }
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory\n", name.c_str());
    return kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", name.c_str(), e.what());
    return kExitFailure;
  }
}

}  // namespace bw::cli
