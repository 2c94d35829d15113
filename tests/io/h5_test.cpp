// The HDF5 layer: typed round trips, kinds and versions, atomic writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/h5.h"
#include "test_support.h"

namespace {

using bw::test::TempDir;
namespace h5 = bw::h5;

template <class T>
void round_trip_type(h5::Group& g, const std::string& name) {
  std::vector<T> values(12);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<T>(i * 3 + 1);
  g.write<T>(name, values, {4, 3});
  g.set_attr<T>(name + "_scalar", static_cast<T>(7));
  g.set_attr<T>(name + "_array", std::span<const T>(values.data(), 3));
}

template <class T>
void check_type(const h5::Group& g, const std::string& name) {
  h5::Shape shape;
  const std::vector<T> values = g.read<T>(name, &shape);
  EXPECT_EQ(shape, (h5::Shape{4, 3})) << name;
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(values[i], static_cast<T>(i * 3 + 1)) << name;
  EXPECT_EQ(g.attr<T>(name + "_scalar"), static_cast<T>(7));
  const std::vector<T> array = g.attr_array<T>(name + "_array");
  EXPECT_EQ(array, (std::vector<T>{1, 4, 7}));
}

TEST(H5, RoundTripOfEveryTypeAndAttribute) {
  TempDir dir;
  const std::string path = dir.file("all.h5");
  {
    h5::File file = h5::File::create(path, "particles");
    h5::Group g = file.root().create_group("data");
    round_trip_type<float>(g, "f32");
    round_trip_type<double>(g, "f64");
    round_trip_type<std::int8_t>(g, "i8");
    round_trip_type<std::uint8_t>(g, "u8");
    round_trip_type<std::int32_t>(g, "i32");
    round_trip_type<std::uint32_t>(g, "u32");
    round_trip_type<std::int64_t>(g, "i64");
    round_trip_type<std::uint64_t>(g, "u64");
    g.set_attr("text", std::string("héllo wörld"));
    g.set_attr("empty_text", "");
    g.write<float>("empty", std::vector<float>{}, {0, 3});
    g.write<double>("compressed", std::vector<double>(100000, 1.5), {}, 4);
    g.create_group("nested").create_group("deeper").set_attr("x", 1.0);
    file.commit();
  }
  const h5::File file = h5::File::open(path, "particles");
  EXPECT_EQ(file.kind(), "particles");
  EXPECT_EQ(file.format_version(), h5::kFormatVersion);
  const h5::Group g = file.root().open_group("data");
  check_type<float>(g, "f32");
  check_type<double>(g, "f64");
  check_type<std::int8_t>(g, "i8");
  check_type<std::uint8_t>(g, "u8");
  check_type<std::int32_t>(g, "i32");
  check_type<std::uint32_t>(g, "u32");
  check_type<std::int64_t>(g, "i64");
  check_type<std::uint64_t>(g, "u64");
  // Conversion on read between numeric types.
  EXPECT_EQ(g.read<double>("i32")[2], 7.0);
  EXPECT_EQ(g.attr_string("text"), "héllo wörld");
  EXPECT_EQ(g.attr_string("empty_text"), "");
  EXPECT_EQ(g.shape("empty"), (h5::Shape{0, 3}));
  EXPECT_TRUE(g.read<float>("empty").empty());
  EXPECT_EQ(g.read<double>("compressed").size(), 100000u);
  EXPECT_EQ(g.read<double>("compressed")[99999], 1.5);
  EXPECT_TRUE(g.has("nested/deeper"));
  EXPECT_FALSE(g.has("nested/missing/more"));
  EXPECT_TRUE(g.is_group("nested"));
  EXPECT_EQ(g.open_group("nested").open_group("deeper").attr<double>("x"), 1.0);
  EXPECT_EQ(g.info("f32").type, "float32");
  EXPECT_EQ(g.info("u64").type, "uint64");
  std::size_t rows = 0;
  EXPECT_EQ(g.read_rows<float>("f32", 3, &rows).size(), 12u);
  EXPECT_EQ(rows, 4u);
}

std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const bw::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(H5, ErrorsNameTheFileAndWhatIsWrong) {
  TempDir dir;
  const std::string path = dir.file("frame.h5");
  {
    h5::File file = h5::File::create(path, "frame");
    file.root().write<float>("x", std::vector<float>{1, 2, 3});
    file.commit();
  }
  const std::string kind = input_error([&] { h5::File::open(path, "particles"); });
  EXPECT_NE(kind.find(path), std::string::npos);
  EXPECT_NE(kind.find("'frame'"), std::string::npos);
  EXPECT_NE(kind.find("'particles'"), std::string::npos);

  const h5::File file = h5::File::open(path);
  const std::string shape = input_error([&] { file.root().read_rows<float>("x", 3, nullptr); });
  EXPECT_NE(shape.find(path + ":/x"), std::string::npos) << shape;
  EXPECT_NE(shape.find("N x 3"), std::string::npos) << shape;
  const std::string missing = input_error([&] { file.root().read<float>("nothere"); });
  EXPECT_NE(missing.find(path + ":/nothere"), std::string::npos) << missing;
  const std::string attr = input_error([&] { file.root().attr<double>("nothere"); });
  EXPECT_NE(attr.find("nothere"), std::string::npos) << attr;
}

TEST(H5, NewerVersionAndForeignFilesAreRefused) {
  TempDir dir;
  const std::string newer = dir.file("newer.h5");
  {
    h5::File file = h5::File::create(newer, "run");
    file.root().set_attr<std::int32_t>("format_version", h5::kFormatVersion + 1);
    file.commit();
  }
  const std::string version = input_error([&] { h5::File::open(newer, "run"); });
  EXPECT_NE(version.find("newer"), std::string::npos) << version;

  const std::string foreign = dir.file("foreign.h5");
  {
    h5::File file = h5::File::create(foreign, "run");
    file.root().set_attr("format", "something-else");
    file.commit();
  }
  EXPECT_NE(input_error([&] { h5::File::open(foreign); }).find("not a breakwater file"), std::string::npos);

  std::ofstream(dir.file("text.h5")) << "just text\n";
  EXPECT_NE(input_error([&] { h5::File::open(dir.file("text.h5")); }).find("not an HDF5 file"), std::string::npos);
  EXPECT_NE(input_error([&] { h5::File::open(dir.file("missing.h5")); }).find("cannot open"), std::string::npos);
  EXPECT_EQ(input_error([&] { h5::File::open(dir.path()); }), dir.path() + ": is a folder, not an HDF5 file");
  // A bw-sim output folder or its frames folder, given for a file, points to the file meant.
  std::filesystem::create_directories(dir.file("out/frames"));
  std::ofstream(dir.file("out/run.h5")) << "x";
  std::ofstream(dir.file("out/frames/000012.h5")) << "x";
  std::ofstream(dir.file("out/frames/000003.h5")) << "x";
  EXPECT_EQ(input_error([&] { h5::File::open(dir.file("out")); }),
            dir.file("out") + ": is a folder, not an HDF5 file (a bw-sim output folder; its run file is " +
                dir.file("out/run.h5") + ")");
  EXPECT_EQ(input_error([&] { h5::File::open(dir.file("out/frames")); }),
            dir.file("out/frames") + ": is a folder, not an HDF5 file (a folder of frames, such as " +
                dir.file("out/frames/000003.h5") + ")");
}

TEST(H5, TruncatedFileIsRefused) {
  TempDir dir;
  const std::string path = dir.file("big.h5");
  {
    h5::File file = h5::File::create(path, "frame");
    file.root().write<double>("x", std::vector<double>(200000, 2.0));
    file.commit();
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  const std::string error = input_error([&] {
    const h5::File file = h5::File::open(path);
    file.root().read<double>("x");
  });
  EXPECT_NE(error.find(path), std::string::npos) << error;
}

TEST(H5, UncommittedFileLeavesNothingAndKeepsThePreviousFile) {
  TempDir dir;
  const std::string path = dir.file("out.h5");
  std::ofstream(path) << "previous content";
  {
    h5::File file = h5::File::create(path, "frame");
    file.root().write<double>("x", std::vector<double>(10, 1.0));
    // No commit: as if an error was thrown here.
  }
  EXPECT_EQ(bw::test::list_folder(dir.path()), "out.h5");
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "previous content");
}

TEST(H5, SameContentGivesSameBytes) {
  TempDir dir;
  auto write = [&](const std::string& path) {
    h5::File file = h5::File::create(path, "frame");
    h5::Group g = file.root().create_group("Step#0");
    g.set_attr("time", 0.5);
    g.write<float>("x", std::vector<float>(1000, 0.25f));
    file.commit();
  };
  write(dir.file("a.h5"));
  write(dir.file("b.h5"));
  auto bytes = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(bytes(dir.file("a.h5")), bytes(dir.file("b.h5")));
}

TEST(H5, CreateRefusesAMissingFolder) {
  TempDir dir;
  const std::string error = input_error([&] { h5::File::create(dir.file("no/such/folder/x.h5"), "frame"); });
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
}

}  // namespace
