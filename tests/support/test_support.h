// Helpers shared by the tests: temporary folders, running the tools, figures.
#pragma once

#include <functional>
#include <string>

namespace bw::test {

// A fresh folder under the system's temporary folder, removed with its contents
// when the object goes.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string out;   // standard output
  std::string err;   // standard error
};

// Runs `command` with /bin/sh, capturing stdout and stderr.
CommandResult run(const std::string& command);

// Path of a built tool, e.g. tool("bw-sample").
std::string tool(const std::string& name);

// True when a file exists.
bool exists(const std::string& path);

// Lists the files of a folder, names only, sorted.
std::string list_folder(const std::string& path);

// A file's bytes ("" when it cannot be read).
std::string file_bytes(const std::string& path);

// The message of the InputError that `f` throws; "(no InputError)" when it throws none.
std::string input_error_of(const std::function<void()>& f);

// Prints a figure the test measured ("[ figure ] name: value") so that it shows in
// the test log next to the assertion that bounds it.
void figure(const std::string& name, double value, const std::string& unit = "");

// Number of lines in a text.
int line_count(const std::string& text);

}  // namespace bw::test
