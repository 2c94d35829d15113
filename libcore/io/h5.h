// The HDF5 file layer: the only part of breakwater that includes hdf5.h.
//
// Every breakwater file carries three root attributes: `format` ("breakwater"),
// `format_version` (an integer, kFormatVersion when written) and `kind` ("particles",
// "frame", "run", "fragments"). File::open checks them and says clearly when a file
// is of another kind or of a newer version. docs/formats.md is the contract.
//
// Writing goes through a temporary file in the same folder that is renamed over the
// final name by File::commit(); a File destroyed without commit leaves nothing
// behind. The name "-" means standard input (open) or standard output (create): the
// file is then held in memory as an HDF5 file image, so tools compose in pipes.
//
// Datasets are row-major with an explicit shape (e.g. N x 3 positions). Object
// modification times are not stored, so the same content gives the same bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/atomic_file.h"

namespace bw::h5 {

inline constexpr std::string_view kFormatName = "breakwater";
inline constexpr int kFormatVersion = 1;

// Element types that datasets and attributes hold.
template <class T>
concept Element =
    std::is_same_v<T, float> || std::is_same_v<T, double> || std::is_same_v<T, std::int8_t> ||
    std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::int32_t> ||
    std::is_same_v<T, std::uint32_t> || std::is_same_v<T, std::int64_t> ||
    std::is_same_v<T, std::uint64_t>;

using Shape = std::vector<std::uint64_t>;

// What a link in a group points at, for listings (bw-info).
struct ObjectInfo {
  bool is_group = false;
  Shape shape;          // datasets only
  std::string type;     // "float32", "int32", "string", ... (datasets only)
};

struct AttrInfo {
  enum class Class { integer, floating, string, other } cls = Class::other;
  std::uint64_t count = 0;  // number of elements (1 for a scalar)
};

// Reference-counted HDF5 identifier (an hid_t), closed when the last copy goes.
class Id {
 public:
  Id() = default;
  explicit Id(std::int64_t id) : id_(id) {}
  ~Id();
  Id(const Id& other);
  Id& operator=(const Id& other);
  Id(Id&& other) noexcept : id_(other.id_) { other.id_ = -1; }
  Id& operator=(Id&& other) noexcept;
  std::int64_t get() const { return id_; }
  bool valid() const;
  // Gives up the reference without releasing it, for a call that does (H5Fclose): a
  // failed close (a full disk) may leave the id registered, and releasing it again
  // would run HDF5's close a second time on a broken file.
  std::int64_t release() {
    const std::int64_t id = id_;
    id_ = -1;
    return id;
  }

 private:
  std::int64_t id_ = -1;
};

class Group {
 public:
  Group() = default;
  Group(Id id, std::string file, std::string path)
      : id_(std::move(id)), file_(std::move(file)), path_(std::move(path)) {}

  // "file.h5:/group" for messages.
  std::string where() const { return file_ + ":" + path_; }
  std::string where(std::string_view child) const;
  const std::string& path() const { return path_; }
  const std::string& file_name() const { return file_; }

  bool has(std::string_view name) const;
  bool is_group(std::string_view name) const;
  Group create_group(std::string_view name);
  // Throws InputError naming the file and path when the group is missing.
  Group open_group(std::string_view name) const;
  // Child names in name order.
  std::vector<std::string> children() const;
  ObjectInfo info(std::string_view name) const;

  // Writes a dataset of the given shape (default: 1-D of data.size()); the product of
  // the shape must equal data.size(). deflate_level 1..9 compresses (chunked).
  template <Element T>
  void write(std::string_view name, std::span<const T> data, Shape shape = {},
             int deflate_level = 0);
  template <Element T>
  void write(std::string_view name, const std::vector<T>& data, Shape shape = {},
             int deflate_level = 0) {
    write<T>(name, std::span<const T>(data), std::move(shape), deflate_level);
  }

  Shape shape(std::string_view name) const;
  // Reads a whole dataset, converting to T (HDF5 converts between numeric types).
  template <Element T>
  std::vector<T> read(std::string_view name, Shape* shape = nullptr) const;
  // Reads a dataset that must be rows x cols (cols == 0: 1-D); throws InputError
  // naming the path and the shape found otherwise.
  template <Element T>
  std::vector<T> read_rows(std::string_view name, std::size_t cols, std::size_t* rows) const;

  bool has_attr(std::string_view name) const;
  std::vector<std::string> attr_names() const;
  AttrInfo attr_info(std::string_view name) const;

  template <Element T>
  void set_attr(std::string_view name, T value);
  template <Element T>
  void set_attr(std::string_view name, std::span<const T> values);
  void set_attr(std::string_view name, std::string_view text);
  void set_attr(std::string_view name, const char* text) { set_attr(name, std::string_view(text)); }
  void set_attr(std::string_view name, const std::string& text) { set_attr(name, std::string_view(text)); }

  // Throw InputError naming the file, path and attribute when it is missing or of
  // another size.
  template <Element T>
  T attr(std::string_view name) const;
  template <Element T>
  std::vector<T> attr_array(std::string_view name) const;
  std::string attr_string(std::string_view name) const;

  std::int64_t id() const { return id_.get(); }

 private:
  Id id_;
  std::string file_;
  std::string path_;
};

class File {
 public:
  // Creates a new file of the given kind ("-": standard output on commit). Checks at
  // once that the folder is writable. Throws InputError on a bad path.
  static File create(const std::string& path, std::string_view kind);
  // Opens a breakwater file ("-": standard input). With `expected_kind` non-empty,
  // a file of another kind is an InputError that says which kind it is.
  static File open(const std::string& path, std::string_view expected_kind = {});

  File(File&& other) noexcept;
  File& operator=(File&& other) noexcept;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File();

  Group& root() { return root_; }
  const Group& root() const { return root_; }
  const std::string& kind() const { return kind_; }
  int format_version() const { return version_; }
  // The path given, or "<stdin>" / "<stdout>".
  const std::string& name() const { return name_; }

  // Finishes a created file: flushes, closes, renames it into place (or writes it to
  // standard output). Throws RunError on failure; then nothing is left behind.
  void commit();

 private:
  File() = default;
  void close() noexcept;

  Id file_;
  Group root_;
  std::string name_;
  std::string kind_;
  int version_ = 0;
  bool writing_ = false;
  bool to_stdout_ = false;
  std::unique_ptr<AtomicFile> target_;  // the final file, written through a temporary
};

// True when `path` names an HDF5 file (by its signature), false for any other file.
bool is_hdf5_file(const std::string& path);

}  // namespace bw::h5
