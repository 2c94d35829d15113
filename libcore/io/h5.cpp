#include "io/h5.h"

#include <hdf5.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>

#include "common/error.h"
#include "common/input_file.h"
#include "common/terminal.h"
#include "io/frame_range.h"

static_assert(std::is_same_v<hid_t, std::int64_t>, "h5.h stores hid_t as int64_t");

namespace bw::h5 {
namespace {

// HDF5 prints its error stack on stderr by default; breakwater reports its own
// one-line messages instead. Called before the first HDF5 call of every entry point.
void quiet_hdf5() {
  static const bool done = [] {
    // Every file is closed by its File. HDF5's own clean-up at exit would close again
    // a file whose close failed (a full disk), which crashes in HDF5 1.10.
    H5dont_atexit();
    H5open();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

// The innermost message of HDF5's error stack ("unable to open file", ...).
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
        if (n == 0 && e->desc) *static_cast<std::string*>(data) = e->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  if (reason.empty()) return "HDF5 error";
  // A failed system call comes as a report over several lines ("file write failed:
  // time = ..., filename = ..., errno = 28, error message = 'No space left on
  // device', ..."): its head and the system's words are what a user needs.
  const std::string marker = "error message = '";
  if (const auto at = reason.find(marker); at != std::string::npos) {
    const auto from = at + marker.size();
    const auto to = reason.find('\'', from);
    const auto colon = reason.find(':');
    reason = reason.substr(0, colon) + ": " + reason.substr(from, to == std::string::npos ? to : to - from);
  }
  for (char& c : reason)
    if (c == '\n') c = ' ';
  return reason;
}

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, float>) return H5T_NATIVE_FLOAT;
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int8_t>) return H5T_NATIVE_INT8;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_NATIVE_UINT8;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
}

// Little-endian file types, so files are the same bytes on every machine.
template <class T>
hid_t file_type() {
  if constexpr (std::is_same_v<T, float>) return H5T_IEEE_F32LE;
  if constexpr (std::is_same_v<T, double>) return H5T_IEEE_F64LE;
  if constexpr (std::is_same_v<T, std::int8_t>) return H5T_STD_I8LE;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_STD_U8LE;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_STD_I32LE;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_STD_U32LE;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_STD_I64LE;
  if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_STD_U64LE;
}

Id check_id(hid_t id, const std::string& what) {
  if (id < 0) fail_run("{}: {}", what, hdf5_reason());
  return Id(id);
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) fail_run("{}: {}", what, hdf5_reason());
}

std::string name_z(std::string_view name) { return std::string(name); }

// Creation properties without modification times: same content, same bytes.
Id object_creation_plist(hid_t cls) {
  Id plist = check_id(H5Pcreate(cls), "H5Pcreate");
  H5Pset_obj_track_times(plist.get(), 0);
  return plist;
}

std::string type_name(hid_t type) {
  switch (H5Tget_class(type)) {
    case H5T_INTEGER: {
      const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
      return fmt::format("{}int{}", is_signed ? "" : "u", 8 * H5Tget_size(type));
    }
    case H5T_FLOAT: return fmt::format("float{}", 8 * H5Tget_size(type));
    case H5T_STRING: return "string";
    default: return "other";
  }
}

Shape space_shape(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank <= 0) return {};
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return Shape(dims.begin(), dims.end());
}

std::uint64_t element_count(const Shape& shape) {
  std::uint64_t n = 1;
  for (auto d : shape) n *= d;
  return n;
}

std::string shape_text(const Shape& shape) {
  if (shape.empty()) return "scalar";
  std::string text;
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? " x " : "") + std::to_string(shape[i]);
  return text;
}

std::vector<char> read_all_stdin() {
  std::vector<char> bytes;
  char buffer[1 << 16];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
  return bytes;
}

constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

// HDF5 looks for its signature at 0, 512, 1024, 2048, ... (a user block may come first).
bool has_signature(const std::vector<char>& head) {
  for (std::size_t offset = 0; offset + 8 <= head.size(); offset = offset ? offset * 2 : 512) {
    if (std::memcmp(head.data() + offset, kSignature, 8) == 0) return true;
  }
  return false;
}

}  // namespace

// ---------------------------------------------------------------------------- Id

Id::~Id() {
  if (valid()) H5Idec_ref(id_);
}

Id::Id(const Id& other) : id_(other.id_) {
  if (valid()) H5Iinc_ref(id_);
}

Id& Id::operator=(const Id& other) {
  if (this != &other) {
    Id copy(other);
    std::swap(id_, copy.id_);
  }
  return *this;
}

Id& Id::operator=(Id&& other) noexcept {
  if (this != &other) {
    if (valid()) H5Idec_ref(id_);
    id_ = other.id_;
    other.id_ = -1;
  }
  return *this;
}

bool Id::valid() const { return id_ >= 0 && H5Iis_valid(id_) > 0; }

// ------------------------------------------------------------------------- Group

std::string Group::where(std::string_view child) const {
  return file_ + ":" + (path_ == "/" ? "" : path_) + "/" + std::string(child);
}

bool Group::has(std::string_view name) const {
  const std::string n = name_z(name);
  // H5Lexists fails on intermediate components that are missing; check each in turn.
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = n.find('/', start);
    const std::string prefix = n.substr(0, slash);
    if (H5Lexists(id_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (slash == std::string::npos) return true;
    start = slash + 1;
  }
}

bool Group::is_group(std::string_view name) const {
  if (!has(name)) return false;
  H5O_info_t info;
  if (H5Oget_info_by_name(id_.get(), name_z(name).c_str(), &info, H5P_DEFAULT) < 0) return false;
  return info.type == H5O_TYPE_GROUP;
}

Group Group::create_group(std::string_view name) {
  Id gcpl = object_creation_plist(H5P_GROUP_CREATE);
  // Links in creation order are not needed; name order keeps listings stable.
  Id id = check_id(H5Gcreate2(id_.get(), name_z(name).c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                   where(name) + ": cannot create group");
  return Group(std::move(id), file_, path_ == "/" ? "/" + name_z(name) : path_ + "/" + name_z(name));
}

Group Group::open_group(std::string_view name) const {
  if (!is_group(name)) fail_input("{}: missing group", where(name));
  Id id = check_id(H5Gopen2(id_.get(), name_z(name).c_str(), H5P_DEFAULT), where(name));
  return Group(std::move(id), file_, path_ == "/" ? "/" + name_z(name) : path_ + "/" + name_z(name));
}

std::vector<std::string> Group::children() const {
  std::vector<std::string> names;
  H5Literate(
      id_.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

ObjectInfo Group::info(std::string_view name) const {
  ObjectInfo result;
  if (!has(name)) fail_input("{}: missing", where(name));
  if (is_group(name)) {
    result.is_group = true;
    return result;
  }
  Id dataset = check_id(H5Dopen2(id_.get(), name_z(name).c_str(), H5P_DEFAULT), where(name));
  Id space = check_id(H5Dget_space(dataset.get()), where(name));
  Id type = check_id(H5Dget_type(dataset.get()), where(name));
  result.shape = space_shape(space.get());
  result.type = type_name(type.get());
  return result;
}

template <Element T>
void Group::write(std::string_view name, std::span<const T> data, Shape shape, int deflate_level) {
  if (shape.empty()) shape = {data.size()};
  if (element_count(shape) != data.size()) {
    fail_run("{}: shape {} does not hold {} values", where(name), shape_text(shape), data.size());
  }
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  Id space = check_id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), where(name));
  Id dcpl = object_creation_plist(H5P_DATASET_CREATE);
  if (deflate_level > 0 && !data.empty()) {
    std::vector<hsize_t> chunk = dims;
    // About 256 KiB per chunk along the first axis.
    std::uint64_t row = element_count(shape) / std::max<std::uint64_t>(1, shape[0]) * sizeof(T);
    chunk[0] = std::clamp<hsize_t>((256 * 1024) / std::max<std::uint64_t>(1, row), 1, dims[0]);
    H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), static_cast<unsigned>(deflate_level));
  }
  Id dataset = check_id(H5Dcreate2(id_.get(), name_z(name).c_str(), file_type<T>(), space.get(),
                                   H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                        where(name) + ": cannot create dataset");
  if (!data.empty()) {
    check_status(H5Dwrite(dataset.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                 where(name) + ": write failed");
  }
}

Shape Group::shape(std::string_view name) const {
  if (!has(name) || is_group(name)) fail_input("{}: missing dataset", where(name));
  Id dataset = check_id(H5Dopen2(id_.get(), name_z(name).c_str(), H5P_DEFAULT), where(name));
  Id space = check_id(H5Dget_space(dataset.get()), where(name));
  return space_shape(space.get());
}

template <Element T>
std::vector<T> Group::read(std::string_view name, Shape* shape_out) const {
  if (!has(name) || is_group(name)) fail_input("{}: missing dataset", where(name));
  Id dataset = check_id(H5Dopen2(id_.get(), name_z(name).c_str(), H5P_DEFAULT), where(name));
  Id space = check_id(H5Dget_space(dataset.get()), where(name));
  Id type = check_id(H5Dget_type(dataset.get()), where(name));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) fail_input("{}: expected numbers, found {}", where(name), type_name(type.get()));
  Shape shape = space_shape(space.get());
  std::vector<T> values(element_count(shape));
  if (!values.empty()) {
    if (H5Dread(dataset.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
      fail_input("{}: cannot read: {}", where(name), hdf5_reason());
    }
  }
  if (shape_out) *shape_out = std::move(shape);
  return values;
}

template <Element T>
std::vector<T> Group::read_rows(std::string_view name, std::size_t cols, std::size_t* rows) const {
  Shape shape;
  std::vector<T> values = read<T>(name, &shape);
  const bool ok = cols == 0 ? shape.size() == 1 : (shape.size() == 2 && shape[1] == cols);
  if (!ok) {
    fail_input("{}: expected shape {}, found {}", where(name), cols == 0 ? "N" : fmt::format("N x {}", cols),
               shape_text(shape));
  }
  if (rows) *rows = shape[0];
  return values;
}

bool Group::has_attr(std::string_view name) const {
  const htri_t exists = H5Aexists(id_.get(), name_z(name).c_str());
  if (exists < 0) H5Eclear2(H5E_DEFAULT);
  return exists > 0;
}

std::vector<std::string> Group::attr_names() const {
  std::vector<std::string> names;
  H5Aiterate2(
      id_.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

AttrInfo Group::attr_info(std::string_view name) const {
  if (!has_attr(name)) fail_input("{}: missing attribute '{}'", where(), name);
  Id attr = check_id(H5Aopen(id_.get(), name_z(name).c_str(), H5P_DEFAULT), where());
  Id type = check_id(H5Aget_type(attr.get()), where());
  Id space = check_id(H5Aget_space(attr.get()), where());
  AttrInfo info;
  switch (H5Tget_class(type.get())) {
    case H5T_INTEGER: info.cls = AttrInfo::Class::integer; break;
    case H5T_FLOAT: info.cls = AttrInfo::Class::floating; break;
    case H5T_STRING: info.cls = AttrInfo::Class::string; break;
    default: info.cls = AttrInfo::Class::other;
  }
  info.count = element_count(space_shape(space.get()));
  return info;
}

namespace {

void replace_attr(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
}

}  // namespace

template <Element T>
void Group::set_attr(std::string_view name, T value) {
  const std::string n = name_z(name);
  replace_attr(id_.get(), n);
  Id space = check_id(H5Screate(H5S_SCALAR), where());
  Id attr = check_id(H5Acreate2(id_.get(), n.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     where() + ": cannot create attribute '" + n + "'");
  check_status(H5Awrite(attr.get(), native_type<T>(), &value), where() + ": attribute '" + n + "'");
}

template <Element T>
void Group::set_attr(std::string_view name, std::span<const T> values) {
  const std::string n = name_z(name);
  replace_attr(id_.get(), n);
  const hsize_t dims[1] = {values.size()};
  Id space = check_id(H5Screate_simple(1, dims, nullptr), where());
  Id attr = check_id(H5Acreate2(id_.get(), n.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     where() + ": cannot create attribute '" + n + "'");
  if (!values.empty()) {
    check_status(H5Awrite(attr.get(), native_type<T>(), values.data()), where() + ": attribute '" + n + "'");
  }
}

void Group::set_attr(std::string_view name, std::string_view text) {
  const std::string n = name_z(name);
  replace_attr(id_.get(), n);
  Id type = check_id(H5Tcopy(H5T_C_S1), where());
  H5Tset_size(type.get(), text.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Id space = check_id(H5Screate(H5S_SCALAR), where());
  Id attr = check_id(H5Acreate2(id_.get(), n.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     where() + ": cannot create attribute '" + n + "'");
  std::string buffer(text);
  check_status(H5Awrite(attr.get(), type.get(), buffer.c_str()), where() + ": attribute '" + n + "'");
}

template <Element T>
std::vector<T> Group::attr_array(std::string_view name) const {
  const std::string n = name_z(name);
  if (!has_attr(n)) fail_input("{}: missing attribute '{}'", where(), n);
  Id attr = check_id(H5Aopen(id_.get(), n.c_str(), H5P_DEFAULT), where());
  Id type = check_id(H5Aget_type(attr.get()), where());
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) fail_input("{}: attribute '{}' is not numeric", where(), n);
  Id space = check_id(H5Aget_space(attr.get()), where());
  std::vector<T> values(element_count(space_shape(space.get())));
  if (!values.empty() && H5Aread(attr.get(), native_type<T>(), values.data()) < 0) {
    fail_input("{}: cannot read attribute '{}': {}", where(), n, hdf5_reason());
  }
  return values;
}

template <Element T>
T Group::attr(std::string_view name) const {
  std::vector<T> values = attr_array<T>(name);
  if (values.size() != 1) fail_input("{}: attribute '{}' holds {} values, expected one", where(), name, values.size());
  return values[0];
}

std::string Group::attr_string(std::string_view name) const {
  const std::string n = name_z(name);
  if (!has_attr(n)) fail_input("{}: missing attribute '{}'", where(), n);
  Id attr = check_id(H5Aopen(id_.get(), n.c_str(), H5P_DEFAULT), where());
  Id type = check_id(H5Aget_type(attr.get()), where());
  if (H5Tget_class(type.get()) != H5T_STRING) fail_input("{}: attribute '{}' is not a string", where(), n);
  if (H5Tis_variable_str(type.get()) > 0) {
    // Written by other tools (h5py's default).
    Id memtype = check_id(H5Tcopy(H5T_C_S1), where());
    H5Tset_size(memtype.get(), H5T_VARIABLE);
    H5Tset_cset(memtype.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attr.get(), memtype.get(), &text) < 0) fail_input("{}: cannot read attribute '{}'", where(), n);
    std::string result = text ? text : "";
    H5free_memory(text);
    return result;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string buffer(size + 1, '\0');
  Id memtype = check_id(H5Tcopy(H5T_C_S1), where());
  H5Tset_size(memtype.get(), size + 1);
  H5Tset_strpad(memtype.get(), H5T_STR_NULLTERM);
  H5Tset_cset(memtype.get(), H5Tget_cset(type.get()));  // HDF5 does not convert between character sets
  if (H5Aread(attr.get(), memtype.get(), buffer.data()) < 0) fail_input("{}: cannot read attribute '{}'", where(), n);
  buffer.resize(std::strlen(buffer.c_str()));
  return buffer;
}

#define BW_H5_INSTANTIATE(T)                                                                    \
  template void Group::write<T>(std::string_view, std::span<const T>, Shape, int);              \
  template std::vector<T> Group::read<T>(std::string_view, Shape*) const;                       \
  template std::vector<T> Group::read_rows<T>(std::string_view, std::size_t, std::size_t*) const; \
  template void Group::set_attr<T>(std::string_view, T);                                        \
  template void Group::set_attr<T>(std::string_view, std::span<const T>);                       \
  template T Group::attr<T>(std::string_view) const;                                            \
  template std::vector<T> Group::attr_array<T>(std::string_view) const;
BW_H5_INSTANTIATE(float)
BW_H5_INSTANTIATE(double)
BW_H5_INSTANTIATE(std::int8_t)
BW_H5_INSTANTIATE(std::uint8_t)
BW_H5_INSTANTIATE(std::int32_t)
BW_H5_INSTANTIATE(std::uint32_t)
BW_H5_INSTANTIATE(std::int64_t)
BW_H5_INSTANTIATE(std::uint64_t)
#undef BW_H5_INSTANTIATE

// -------------------------------------------------------------------------- File

namespace {

Id file_access_plist() {
  Id fapl = check_id(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
  // Closing the file closes every object still open in it, so commit() is final.
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  return fapl;
}

Id memory_access_plist() {
  Id fapl = file_access_plist();
  H5Pset_fapl_core(fapl.get(), 1 << 20, /*backing_store=*/0);
  return fapl;
}

}  // namespace

namespace {

// For a folder given as a file: the file a user likely meant in it, a bw-sim output
// folder's run file or a frames folder's first frame.
std::string folder_hint(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path run = fs::path(folder) / "run.h5";
  if (fs::is_regular_file(run, ec)) return fmt::format(" (a bw-sim output folder; its run file is {})", run.string());
  const std::map<int, std::string> frames = frame_files(folder);
  return frames.empty() ? std::string() : fmt::format(" (a folder of frames, such as {})", frames.begin()->second);
}

}  // namespace

bool is_hdf5_file(const std::string& path) {
  std::ifstream in(seekable_path(path), std::ios::binary);
  if (!in) return false;
  std::vector<char> head(8192);
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return has_signature(head);
}

File File::create(const std::string& path, std::string_view kind) {
  quiet_hdf5();
  File file;
  file.writing_ = true;
  file.kind_ = std::string(kind);
  file.version_ = kFormatVersion;
  Id fcpl = object_creation_plist(H5P_FILE_CREATE);
  if (path == "-") {
    if (stdout_is_terminal()) fail_input("-: refusing to write an HDF5 file to a terminal; redirect or pipe standard output");
    file.to_stdout_ = true;
    file.name_ = "<stdout>";
    Id fapl = memory_access_plist();
    file.file_ = check_id(H5Fcreate("breakwater-stdout.h5", H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()),
                          "<stdout>: cannot create an in-memory file");
  } else {
    file.name_ = path;
    file.target_ = std::make_unique<AtomicFile>(path);
    Id fapl = file_access_plist();
    errno = 0;
    const hid_t created = H5Fcreate(file.target_->temp_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
    // The system's reason, not HDF5's report, which names the temporary file and its flags.
    if (created < 0) fail_run("{}: cannot create: {}", path, errno ? std::strerror(errno) : hdf5_reason());
    file.file_ = Id(created);
  }
  Id root = check_id(H5Gopen2(file.file_.get(), "/", H5P_DEFAULT), file.name_);
  file.root_ = Group(std::move(root), file.name_, "/");
  file.root_.set_attr("format", kFormatName);
  file.root_.set_attr<std::int32_t>("format_version", kFormatVersion);
  file.root_.set_attr("kind", kind);
  return file;
}

File File::open(const std::string& path, std::string_view expected_kind) {
  quiet_hdf5();
  File file;
  if (path == "-") {
    file.name_ = "<stdin>";
    std::vector<char> bytes = read_all_stdin();
    if (bytes.empty()) fail_input("<stdin>: empty input, expected an HDF5 file");
    if (!has_signature(bytes)) fail_input("<stdin>: not an HDF5 file");
    Id fapl = memory_access_plist();
    check_status(H5Pset_file_image(fapl.get(), bytes.data(), bytes.size()), "<stdin>");
    file.file_ = Id(H5Fopen("breakwater-stdin.h5", H5F_ACC_RDONLY, fapl.get()));
    if (file.file_.get() < 0) fail_input("<stdin>: cannot read the HDF5 file: {}", hdf5_reason());
  } else {
    file.name_ = path;
    const std::string source = seekable_path(path);  // a pipe's copy: HDF5 seeks
    std::ifstream probe(source, std::ios::binary);
    if (!probe) fail_input("{}: cannot open: {}", path, std::strerror(errno));
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      fail_input("{}: is a folder, not an HDF5 file{}", path, folder_hint(path));
    if (!is_hdf5_file(source)) fail_input("{}: not an HDF5 file", path);
    Id fapl = file_access_plist();
    file.file_ = Id(H5Fopen(source.c_str(), H5F_ACC_RDONLY, fapl.get()));
    if (file.file_.get() < 0) fail_input("{}: cannot read the HDF5 file: {}", path, hdf5_reason());
  }
  Id root = check_id(H5Gopen2(file.file_.get(), "/", H5P_DEFAULT), file.name_);
  file.root_ = Group(std::move(root), file.name_, "/");
  const Group& r = file.root_;
  if (!r.has_attr("format") || r.attr_info("format").cls != AttrInfo::Class::string ||
      r.attr_string("format") != kFormatName) {
    fail_input("{}: not a breakwater file (no format=\"breakwater\" attribute)", file.name_);
  }
  if (!r.has_attr("format_version") || !r.has_attr("kind")) {
    fail_input("{}: breakwater file without 'format_version' or 'kind' attribute", file.name_);
  }
  file.version_ = r.attr<std::int32_t>("format_version");
  file.kind_ = r.attr_string("kind");
  if (file.version_ > kFormatVersion) {
    fail_input("{}: format_version {} is newer than this breakwater reads ({}); update breakwater", file.name_,
               file.version_, kFormatVersion);
  }
  if (!expected_kind.empty() && file.kind_ != expected_kind) {
    fail_input("{}: is a '{}' file, expected a '{}' file", file.name_, file.kind_, expected_kind);
  }
  return file;
}

File::File(File&& other) noexcept
    : file_(std::move(other.file_)),
      root_(std::move(other.root_)),
      name_(std::move(other.name_)),
      kind_(std::move(other.kind_)),
      version_(other.version_),
      writing_(other.writing_),
      to_stdout_(other.to_stdout_),
      target_(std::move(other.target_)) {
  other.writing_ = false;
}

File& File::operator=(File&& other) noexcept {
  if (this != &other) {
    close();
    file_ = std::move(other.file_);
    root_ = std::move(other.root_);
    name_ = std::move(other.name_);
    kind_ = std::move(other.kind_);
    version_ = other.version_;
    writing_ = other.writing_;
    to_stdout_ = other.to_stdout_;
    target_ = std::move(other.target_);
    other.writing_ = false;
  }
  return *this;
}

File::~File() { close(); }

void File::close() noexcept {
  root_ = Group();
  if (file_.valid()) H5Fclose(file_.release());
  file_ = Id();
  target_.reset();  // removes an uncommitted temporary file
}

void File::commit() {
  if (!writing_) fail_run("{}: commit() on a file opened for reading", name_);
  root_ = Group();
  if (to_stdout_) {
    check_status(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), name_ + ": flush failed");
    const ssize_t size = H5Fget_file_image(file_.get(), nullptr, 0);
    if (size < 0) fail_run("{}: cannot take the file image: {}", name_, hdf5_reason());
    std::vector<char> image(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file_.get(), image.data(), image.size()) < 0) {
      fail_run("{}: cannot take the file image: {}", name_, hdf5_reason());
    }
    H5Fclose(file_.release());
    if (std::fwrite(image.data(), 1, image.size(), stdout) != image.size() || std::fflush(stdout) != 0) {
      fail_run("<stdout>: write failed: {}", std::strerror(errno));
    }
  } else {
    const herr_t closed = H5Fclose(file_.release());
    if (closed < 0) fail_run("{}: closing failed: {}", name_, hdf5_reason());
    target_->commit();
    target_.reset();
  }
  writing_ = false;
}

}  // namespace bw::h5
