// Writing a file so that it appears under its final name only when complete.
//
// The data goes to a temporary file in the same folder (so that rename is atomic on
// POSIX file systems); commit() renames it over the final name. If the object is
// destroyed without commit (an exception, a failed run), the temporary file is
// removed and whatever stood under the final name before is untouched; so it is when
// SIGINT, SIGTERM or SIGHUP stops the tool (common/temp_files.h).
//
// A final name that is a symbolic link is written through: the file it points to is
// replaced and the link stays. One that is a device or a pipe (/dev/null, a FIFO,
// /dev/stdout) cannot be renamed over, and must not be: the temporary file goes to
// the system's temporary folder and commit() copies it in.
#pragma once

#include <string>
#include <vector>

namespace bw {

class AtomicFile {
 public:
  // Throws InputError when the folder of `path` does not exist or is not writable.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;

  const std::string& final_path() const { return final_path_; }
  const std::string& temp_path() const { return temp_path_; }

  // Renames the temporary file to the final name (or copies it into a device or a
  // pipe). Throws RunError on failure.
  void commit();
  // Removes the temporary file now (also done by the destructor).
  void discard() noexcept;

 private:
  std::string final_path_;   // as given, for messages
  std::string target_path_;  // where the bytes go: final_path_ with a link followed
  std::string temp_path_;
  bool stream_ = false;      // the target is a device or a pipe: copied in, not renamed
  bool committed_ = false;
  int ticket_ = -1;          // the temporary file's, for removal on a signal (temp_files.h)
};

// Copies the whole of the file `from` (a pipe too) into the open file `fd`; returns 0
// or the errno of the failure.
int copy_file_into(const std::string& from, int fd);

// Writes `bytes` to `path` through an AtomicFile.
void write_file_atomically(const std::string& path, const void* bytes, std::size_t size);

// Throws InputError naming `path` unless its folder exists and is writable.
void check_writable_folder_of(const std::string& path);

// What AtomicFile(path) checks, for a tool to call before its work so that a bad -o
// is refused at once: the folder of `path` exists and is writable, and `path` is no
// folder (or, for a device or a pipe, it is writable). "-" (standard output) passes.
// `inputs` are the files the tool reads: an output that is one of them (by another
// name or through a link too) would replace what it was made from, and is refused.
void check_output_file(const std::string& path, const std::vector<std::string>& inputs = {});

}  // namespace bw
