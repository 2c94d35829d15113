#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"

namespace bw::test {
namespace fs = std::filesystem;

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  const fs::path base = fs::temp_directory_path();
  path_ = (base / fmt::format("bw-test-{}-{}", ::getpid(), counter++)).string();
  fs::remove_all(path_);
  fs::create_directories(path_);
}

// BW_TEST_KEEP=1 keeps the folders, to look at a failed test's scenes and runs.
TempDir::~TempDir() {
  if (const char* keep = std::getenv("BW_TEST_KEEP"); keep && std::string(keep) == "1") {
    std::fprintf(stderr, "kept %s\n", path_.c_str());
    return;
  }
  std::error_code ec;
  fs::remove_all(path_, ec);
}

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

CommandResult run(const std::string& command) {
  TempDir capture;
  const std::string out = capture.file("out"), err = capture.file("err");
  const std::string full = "( " + command + " ) >" + out + " 2>" + err;
  const int status = std::system(full.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(out);
  result.err = slurp(err);
  return result;
}

std::string tool(const std::string& name) { return std::string(BW_TOOLS_DIR) + "/" + name + "/" + name; }

bool exists(const std::string& path) { return fs::exists(path); }

std::string list_folder(const std::string& path) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(path)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : " ") + n;
  return text;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

void figure(const std::string& name, double value, const std::string& unit) {
  std::printf("[ figure   ] %s: %.6g%s%s\n", name.c_str(), value, unit.empty() ? "" : " ", unit.c_str());
  std::fflush(stdout);
}

int line_count(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + (!text.empty() && text.back() != '\n');
}

}  // namespace bw::test
