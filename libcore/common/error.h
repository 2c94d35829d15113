// Exceptions thrown by libcore and the exit codes the tools map them to.
//
// libcore throws; each tool catches once in main (cli/tool.h) and prints
// "bw-tool: <message>" on one line of stderr. Messages name the thing at fault:
// "scene.toml: solid[2].frc: 1.4 is outside (0, 1]".
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace bw {

// Exit codes shared by every tool (documented in docs/tools.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,      // something failed while running (device error, blow-up)
  kExitBadInput = 2,     // bad usage or bad input; nothing was written
  kExitCheckFailed = 3,  // a checking tool ran and found violations
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  virtual int exit_code() const { return kExitFailure; }
};

// Bad usage or bad input: a value out of range, a malformed or missing file, a file
// of the wrong kind. Exit code 2.
class InputError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return kExitBadInput; }
};

// A failure while running on valid input: I/O failure while writing, a device
// error, a numerical blow-up. Exit code 1.
class RunError : public Error {
 public:
  using Error::Error;
};

template <class... Args>
[[noreturn]] void fail_input(fmt::format_string<Args...> f, Args&&... args) {
  throw InputError(fmt::format(f, std::forward<Args>(args)...));
}

template <class... Args>
[[noreturn]] void fail_run(fmt::format_string<Args...> f, Args&&... args) {
  throw RunError(fmt::format(f, std::forward<Args>(args)...));
}

}  // namespace bw
