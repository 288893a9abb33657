// The HDF5 layer: arrays of every type and rank, attributes, row-wise and
// extendible datasets, and errors that name the file and the dataset.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/io/h5.hpp>

#include <cmath>
#include <fstream>
#include <limits>

using namespace drape;
using drape::test::TempDir;
using drape::test::message_of;

TEST_CASE("h5: arrays of every element type and rank round-trip exactly", "[hdf5]") {
  TempDir dir;
  const auto path = dir / "arrays.h5";
  const std::vector<float> f32 = {1.5f, -2.25f, 3.0e-7f, std::numeric_limits<float>::max(), 0.1f, -0.0f};
  const std::vector<double> f64 = {M_PI, -1e300, 1e-300, 0.1};
  const std::vector<std::int8_t> i8 = {-128, 0, 1, 127};
  const std::vector<std::uint8_t> u8 = {0, 1, 255};
  const std::vector<std::int32_t> i32 = {-2147483647 - 1, 7, 2147483647};
  const std::vector<std::int64_t> i64 = {-(std::int64_t{1} << 62), 5};
  {
    auto file = h5::File::create(path);
    file.write("/a/b/f32", {2, 3}, f32.data());
    file.write("f64", f64);
    file.write("/ints/i8", i8);
    file.write("/ints/u8", u8);
    file.write("/ints/i32", {1, 3, 1}, i32.data());
    file.write("/ints/i64", i64);
    const double scalar = 42.5;
    file.write("/scalar", {}, &scalar);
  }
  const auto file = h5::File::open(path);
  h5::Dims shape;
  CHECK(file.read<float>("/a/b/f32", &shape) == f32);
  CHECK(shape == h5::Dims{2, 3});
  CHECK(file.dtype("/a/b/f32") == h5::DType::F32);
  CHECK(file.read<double>("/f64") == f64);
  CHECK(file.read<std::int8_t>("/ints/i8") == i8);
  CHECK(file.dtype("/ints/i8") == h5::DType::I8);
  CHECK(file.read<std::uint8_t>("/ints/u8") == u8);
  CHECK(file.dtype("/ints/u8") == h5::DType::U8);
  CHECK(file.read<std::int32_t>("/ints/i32", &shape) == i32);
  CHECK(shape == h5::Dims{1, 3, 1});
  CHECK(file.read<std::int64_t>("/ints/i64") == i64);
  CHECK(file.dtype("/ints/i64") == h5::DType::I64);
  CHECK(file.read<double>("/scalar", &shape) == std::vector<double>{42.5});
  CHECK(shape.empty());
  // Reading converts between numeric types.
  CHECK(file.read<double>("/ints/i32") == std::vector<double>{-2147483648.0, 7.0, 2147483647.0});
  CHECK(file.children("/") == std::vector<std::string>{"a", "f64", "ints", "scalar"});
  CHECK(file.datasets_below("/ints") == std::vector<std::string>{"i32", "i64", "i8", "u8"});
  CHECK(file.datasets_below("/a") == std::vector<std::string>{"b/f32"});
  CHECK(file.is_group("/a/b"));
  CHECK_FALSE(file.is_dataset("/a/b"));
  CHECK(file.is_dataset("a/b/f32"));
  CHECK_FALSE(file.exists("/a/nothing/deeper"));
}

TEST_CASE("h5: string and number attributes", "[hdf5]") {
  TempDir dir;
  const auto path = dir / "attrs.h5";
  const std::string yaml = "body: { model: parametric, bmi: 42 }\nname: \"Zoë — ünïcode\"\n";
  {
    auto file = h5::File::create(path);
    file.set_attribute("/", "scene", yaml);
    file.set_attribute("/", "empty", "");
    file.set_attribute("/", "epoch", 12.0);
    file.write("/w", std::vector<float>{1, 2});
    file.set_attribute("/w", "unit", "m");
    file.set_attribute("/", "scene", yaml + "# replaced\n");  // setting twice replaces
  }
  const auto file = h5::File::open(path);
  CHECK(file.string_attribute("/", "scene") == yaml + "# replaced\n");
  CHECK(file.string_attribute("/", "empty") == std::string());
  CHECK(file.number_attribute("/", "epoch") == 12.0);
  CHECK(file.string_attribute("/w", "unit") == std::string("m"));
  CHECK_FALSE(file.string_attribute("/", "nope").has_value());
  CHECK(file.attribute_names("/") == std::vector<std::string>{"empty", "epoch", "scene"});
  CHECK_THROWS_AS(file.string_attribute("/", "epoch"), ConfigError);  // a number, not a string
  CHECK(message_of([&] { file.require_string_attribute("/", "template_hash"); }) ==
        path.string() + ": missing attribute 'template_hash' of /");
}

TEST_CASE("h5: extendible datasets grow along the first axis", "[hdf5]") {
  TempDir dir;
  const auto path = dir / "grow.h5";
  {
    auto file = h5::File::create(path);
    file.create<float>("/log/loss", {0, 2}, {.extendible = true, .chunk_rows = 4});
    for (int i = 0; i < 10; ++i) {
      const float row[2] = {float(i), float(i * i)};
      CHECK(file.append_rows("/log/loss", 1, row) == std::size_t(i));
    }
    const float two[4] = {100, 101, 102, 103};
    file.append_rows("/log/loss", 2, two);
    // Contiguous datasets have a fixed size.
    file.create<double>("/fixed", {3});
    CHECK_THROWS_AS(file.resize_rows("/fixed", 4), Error);
  }
  auto file = h5::File::open(path, h5::Access::ReadWrite);
  h5::Dims shape;
  const auto loss = file.read<float>("/log/loss", &shape);
  REQUIRE(shape == h5::Dims{12, 2});
  for (int i = 0; i < 10; ++i) {
    CHECK(loss[2 * i] == float(i));
    CHECK(loss[2 * i + 1] == float(i * i));
  }
  CHECK(loss[20] == 100);
  CHECK(loss[23] == 103);
  float middle[4];
  file.read_rows("/log/loss", 3, 2, middle);
  CHECK(middle[0] == 3);
  CHECK(middle[3] == 16);
  file.resize_rows("/log/loss", 5);  // shrinking works too
  CHECK(file.shape("/log/loss") == h5::Dims{5, 2});
  CHECK_THROWS_AS(file.read_rows("/log/loss", 4, 2, middle), Error);
}

TEST_CASE("h5: row writes into a preallocated dataset with a fill value", "[hdf5]") {
  TempDir dir;
  const auto path = dir / "rows.h5";
  {
    auto file = h5::File::create(path);
    file.create<double>("/stats/e", {5}, {.preallocate = true, .fill = std::nan("")});
    file.create<std::uint8_t>("/done", {5}, {.preallocate = true, .fill = 0.0});
    const double e = 2.5;
    file.write_rows("/stats/e", 3, 1, &e);
    const std::uint8_t one = 1;
    file.write_rows("/done", 3, 1, &one);
  }
  const auto file = h5::File::open(path);
  const auto e = file.read<double>("/stats/e");
  const auto done = file.read<std::uint8_t>("/done");
  for (int i = 0; i < 5; ++i) {
    CHECK(std::isnan(e[i]) == (i != 3));
    CHECK(done[i] == (i == 3));
  }
  CHECK(e[3] == 2.5);
}

TEST_CASE("h5: bad files and missing things give one clear line", "[hdf5]") {
  TempDir dir;
  SECTION("missing file") {
    const auto p = dir / "absent.h5";
    CHECK(message_of([&] { h5::File::open(p); }) == p.string() + ": no such file");
    CHECK_THROWS_AS(h5::File::open(p), ConfigError);
  }
  SECTION("not an HDF5 file") {
    const auto p = dir / "data.h5";
    std::ofstream(p) << "this is text, not HDF5\n";
    CHECK(message_of([&] { h5::File::open(p); }) == p.string() + ": not an HDF5 file");
    CHECK_THROWS_AS(h5::File::open(p), ConfigError);
  }
  SECTION("truncated file") {
    const auto p = dir / "model.h5";
    {
      auto file = h5::File::create(p);
      file.write("/weights/big", std::vector<double>(4096, 1.0));
    }
    std::filesystem::resize_file(p, 1500);
    // Opening or reading must fail with ConfigError, never crash or print HDF5's stack.
    auto open_and_read = [&] { h5::File::open(p).read<double>("/weights/big"); };
    CHECK_THROWS_AS(open_and_read(), ConfigError);
    CHECK(message_of(open_and_read).rfind(p.string() + ": ", 0) == 0);
  }
  SECTION("missing dataset and wrong shape") {
    const auto p = dir / "model.h5";
    {
      auto file = h5::File::create(p);
      file.write("/weights/encoder/b", std::vector<float>(3, 0.0f));
    }
    const auto file = h5::File::open(p);
    CHECK(message_of([&] { file.read<float>("/weights/encoder/w"); }) == p.string() + ": missing dataset /weights/encoder/w");
    CHECK_THROWS_AS(file.shape("weights/nothing/here"), ConfigError);
    float out[4];
    CHECK(message_of([&] { file.read("/weights/encoder/b", {4}, out); }) ==
          p.string() + ": dataset /weights/encoder/b has shape [3], expected [4]");
  }
  SECTION("writing to a read-only file") {
    const auto p = dir / "ro.h5";
    h5::File::create(p).write("/x", std::vector<float>{1});
    auto file = h5::File::open(p);
    CHECK_THROWS_AS(file.write("/y", std::vector<float>{1}), Error);
  }
}

TEST_CASE("h5: path normalisation", "[hdf5]") {
  CHECK(h5::normalize("") == "/");
  CHECK(h5::normalize("/") == "/");
  CHECK(h5::normalize("a/b") == "/a/b");
  CHECK(h5::normalize("//a///b/") == "/a/b");
}
