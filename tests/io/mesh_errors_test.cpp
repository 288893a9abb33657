// Bad input files give one ConfigError line naming the file (and the line for
// OBJ); a failed write leaves nothing behind.
#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include "mesh_test_util.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace drape;
using drape::test::TempDir;
namespace fs = std::filesystem;

namespace {

// The message of the ConfigError that reading `text` as `name` throws.
std::string obj_error(const std::string& text) {
  TempDir dir;
  drape::test::write_text(dir / "bad.obj", text);
  try {
    read_mesh(dir / "bad.obj");
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    CHECK(message.find('\n') == std::string::npos);
    return message;
  }
  FAIL("no ConfigError for:\n" << text);
  return "";
}

// The message of the ConfigError that `action` throws, or a marker if none.
template <class Action>
std::string config_error(Action&& action) {
  try {
    action();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "<no ConfigError>";
}

int files_in(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
  return n;
}


// Standard base64 (RFC 4648), for a glTF's data URI.
std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = (bytes[i] << 16) | ((i + 1 < bytes.size() ? bytes[i + 1] : 0) << 8) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += abc[(v >> 18) & 63];
    out += abc[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? abc[v & 63] : '=';
  }
  return out;
}

// A glTF written by hand (not by drape's writer): a unit square of 4
// vertices and two triangles with these 6 uint16 indices.
std::string square_gltf(const std::vector<std::uint16_t>& indices) {
  const float xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<unsigned char> bytes(48 + 2 * indices.size());
  std::memcpy(bytes.data(), xyz, 48);
  std::memcpy(bytes.data() + 48, indices.data(), 2 * indices.size());
  const std::string n = std::to_string(2 * indices.size());
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
         R"("buffers":[{"byteLength":)" + std::to_string(bytes.size()) +
         R"(,"uri":"data:application/octet-stream;base64,)" + base64(bytes) + R"("}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":)" + n +
         R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5123,"count":)" + std::to_string(indices.size()) + R"(,"type":"SCALAR"}]})";
}

}  // namespace

TEST_CASE("malformed OBJ files name the file and the line", "[io]") {
  using Catch::Contains;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  CHECK_THAT(obj_error("# x\nv 0 0 0\nv 1 2\n"), Contains("bad.obj:3:") && Contains("three numbers"));
  CHECK_THAT(obj_error(tri + "f 1 2 4\n"), Contains("bad.obj:4:") && Contains("vertex 4"));
  CHECK_THAT(obj_error(tri + "f 1 2 -4\n"), Contains("bad.obj:4:"));
  CHECK_THAT(obj_error(tri + "f 0 1 2\n"), Contains("bad.obj:4:"));
  CHECK_THAT(obj_error(tri + "vt 0 0\nf 1/1 2/2 3/1\n"), Contains("bad.obj:5:") && Contains("texture coordinate 2"));
  CHECK_THAT(obj_error("v 0 nan 0\n"), Contains("bad.obj:1:") && Contains("finite"));
  CHECK_THAT(obj_error("v 0 1e999 0\n"), Contains("bad.obj:1:"));
  CHECK_THAT(obj_error("v 0 0x 0\n"), Contains("bad.obj:1:"));
  CHECK_THAT(obj_error(tri + "f 1 2\n"), Contains("bad.obj:4:") && Contains("2 corners"));
  CHECK_THAT(obj_error(tri + "f 1 2 a\n"), Contains("bad.obj:4:"));
  CHECK_THAT(obj_error(tri + "vt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n"), Contains("bad.obj:6:") && Contains("line 5"));
  CHECK_THAT(obj_error(tri + "vt 0 0\nf 1/1 2 3/1\n"), Contains("bad.obj:5:") && Contains("some corners"));
  CHECK_THAT(obj_error("# nothing\n"), Contains("bad.obj") && Contains("no vertices"));
}

TEST_CASE("missing, corrupt and unknown mesh files give a ConfigError naming the file", "[io]") {
  using Catch::Contains;
  TempDir dir;
  CHECK_THAT(config_error([&] { read_mesh(dir / "absent.ply"); }), Contains("absent.ply: no such file"));
  CHECK_THAT(config_error([&] { read_mesh(dir.path()); }), Contains("folder"));

  drape::test::write_text(dir / "junk.ply", "this is not a ply file at all\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "junk.ply"); }), Contains("junk.ply"));
  drape::test::write_text(dir / "junk.glb", std::string("glTF\x02\0\0\0garbage", 16));
  CHECK_THAT(config_error([&] { read_mesh(dir / "junk.glb"); }), Contains("junk.glb"));
  drape::test::write_text(dir / "junk.gltf", "{ \"asset\": ");
  CHECK_THAT(config_error([&] { read_mesh(dir / "junk.gltf"); }), Contains("junk.gltf"));
  // A glTF cut in half: damaged, not a format drape does not read (assimp
  // says "no suitable reader found", an outside check read it so).
  const std::string whole = square_gltf({0, 1, 2, 0, 2, 3});
  drape::test::write_text(dir / "half.gltf", whole.substr(0, whole.size() / 2));
  CHECK_THAT(config_error([&] { read_mesh(dir / "half.gltf"); }),
             Contains("half.gltf") && Contains("the file is damaged or truncated, or is not the format its name says"));
  drape::test::write_text(dir / "mesh.qqq", "1 2 3\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "mesh.qqq"); }), Contains("mesh.qqq") && Contains("unknown mesh format '.qqq'"));
}

TEST_CASE("a PLY face index out of range is a ConfigError naming the file", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "range.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "range.ply"); }), Catch::Contains("range.ply"));
}

TEST_CASE("a glTF face index out of range is refused, not a mesh with the face dropped", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "square.gltf", square_gltf({0, 1, 2, 0, 2, 3}));
  const Mesh square = read_mesh(dir / "square.gltf");
  CHECK(square.num_vertices() == 4);
  CHECK(square.num_faces() == 2);
  // assimp drops the second face with a warning and reads on.
  drape::test::write_text(dir / "range.gltf", square_gltf({0, 1, 2, 0, 2, 9}));
  CHECK_THAT(config_error([&] { read_mesh(dir / "range.gltf"); }),
             Catch::Contains("range.gltf") && Catch::Contains("out-of-range indices"));
  // The warnings of one file do not follow the next.
  CHECK(read_mesh(dir / "square.gltf").num_faces() == 2);
}

TEST_CASE("a PLY cut short is a ConfigError, not a smaller mesh", "[io]") {
  TempDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  drape::test::write_text(dir / "whole.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK(read_mesh(dir / "whole.ply").num_faces() == 1);
  drape::test::write_text(dir / "cut.ply", header + "0 0 0\n1 0 0\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "cut.ply"); }), Catch::Contains("cut.ply") && Catch::Contains("cut short"));
  // A binary PLY (as write_mesh makes it) cut short.
  write_mesh(dir / "binary.ply", drape::test::shuffled_grid(4, 4, 3));
  CHECK(read_mesh(dir / "binary.ply").num_vertices() == 16);
  std::filesystem::resize_file(dir / "binary.ply", std::filesystem::file_size(dir / "binary.ply") - 10);
  CHECK_THAT(config_error([&] { read_mesh(dir / "binary.ply"); }), Catch::Contains("binary.ply") && Catch::Contains("cut short"));
  drape::test::write_text(dir / "nan.ply", header + "nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "nan.ply"); }), Catch::Contains("nan.ply") && Catch::Contains("finite"));
  // The other way (an outside check): a face count short of the faces that
  // follow was read without the rest, a hole and no message.
  drape::test::write_text(dir / "more.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "more.ply"); }),
             Catch::Contains("more.ply") && Catch::Contains("declares 4 elements but 5 lines follow"));
  write_mesh(dir / "long.ply", drape::test::shuffled_grid(4, 4, 3));
  std::ofstream(dir / "long.ply", std::ios::app | std::ios::binary) << std::string("\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 13);
  CHECK_THAT(config_error([&] { read_mesh(dir / "long.ply"); }),
             Catch::Contains("long.ply") && Catch::Contains("a count in the header is short"));
}

// Found by fuzzing the command line: libassimp's PLY reader loops forever on a
// header cut before end_header, and a count far beyond the file (PLY or OFF)
// had it reserve gigabytes before failing a minute later. Both are refused
// before assimp reads the file.
TEST_CASE("a mesh header cut short or declaring more than the file holds is refused at once", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "header.ply"); }), Catch::Contains("header.ply") && Catch::Contains("end_header"));
  drape::test::write_text(dir / "magic.ply", "ply\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "magic.ply"); }), Catch::Contains("end_header"));
  write_mesh(dir / "binary.ply", drape::test::shuffled_grid(4, 4, 3));
  std::string bytes = drape::test::read_file(dir / "binary.ply");
  const std::string declared = "element vertex 16";
  REQUIRE(bytes.find(declared) != std::string::npos);
  bytes.replace(bytes.find(declared), declared.size(), "element vertex 999999999");
  drape::test::write_text(dir / "huge.ply", bytes);
  CHECK_THAT(config_error([&] { read_mesh(dir / "huge.ply"); }), Catch::Contains("huge.ply") && Catch::Contains("cut short"));

  const std::string tetrahedron = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  drape::test::write_text(dir / "whole.off", tetrahedron);
  const Mesh read = read_mesh(dir / "whole.off");
  CHECK(read.num_vertices() == 4);
  CHECK(read.num_faces() == 4);
  drape::test::write_text(dir / "counts.off", "OFF\n999999999 999999999 0\n0 0 0\n");
  CHECK_THAT(config_error([&] { read_mesh(dir / "counts.off"); }), Catch::Contains("counts.off") && Catch::Contains("cut short"));
  drape::test::write_text(dir / "cut.off", tetrahedron.substr(0, tetrahedron.find("3 0 1 3")));
  CHECK_THAT(config_error([&] { read_mesh(dir / "cut.off"); }), Catch::Contains("cut.off") && Catch::Contains("cut short"));

  // A binary PLY whose header gives one vertex too few: the last vertex is
  // read as faces; refused with the hint to check the header's counts.
  std::string short_count = drape::test::read_file(dir / "binary.ply");
  short_count.replace(short_count.find(declared), declared.size(), "element vertex 15");
  drape::test::write_text(dir / "fewer.ply", short_count);
  CHECK_THAT(config_error([&] { read_mesh(dir / "fewer.ply"); }),
             Catch::Contains("fewer.ply") && Catch::Contains("check the header's element counts against the data"));
  // A .glb whose first chunk claims 2 GiB (assimp read for a minute at 2.1 GB),
  // and one cut short: their lengths are read by hand (glTF 2.0's container:
  // total length at byte 8, the first chunk's length at byte 12).
  write_mesh(dir / "whole.glb", drape::test::shuffled_grid(4, 4, 3));
  const std::string glb = drape::test::read_file(dir / "whole.glb");
  REQUIRE(read_mesh(dir / "whole.glb").num_vertices() == 16);
  std::string claims = glb;
  const std::uint32_t two_gib = 2147483648u;
  std::memcpy(claims.data() + 12, &two_gib, 4);  // (little-endian, as this machine)
  drape::test::write_text(dir / "claims.glb", claims);
  CHECK_THAT(config_error([&] { read_mesh(dir / "claims.glb"); }),
             Catch::Contains("claims.glb") && Catch::Contains("GLB chunk 0 at byte 12 says 2147483648 bytes"));
  drape::test::write_text(dir / "short.glb", glb.substr(0, glb.size() - 10));
  CHECK_THAT(config_error([&] { read_mesh(dir / "short.glb"); }),
             Catch::Contains("short.glb") && Catch::Contains("the GLB header gives the file " + std::to_string(glb.size()) + " bytes"));
}

TEST_CASE("writing into a missing folder throws and creates nothing", "[io]") {
  TempDir dir;
  const Mesh grid = drape::test::shuffled_grid(3, 3, 1);
  for (const char* name : {"out.obj", "out.ply", "out.gltf", "out.glb"}) {
    CHECK_THAT(config_error([&] { write_mesh(dir / "missing" / name, grid); }), Catch::Contains("missing") && Catch::Contains("does not exist"));
  }
  CHECK(files_in(dir.path()) == 0);
  CHECK_THAT(config_error([&] { write_mesh(dir / "out.stl", grid); }), Catch::Contains("'.stl'"));
  CHECK(files_in(dir.path()) == 0);
}

TEST_CASE("a failed write leaves no file and keeps an older one untouched", "[io]") {
  TempDir dir;
  Mesh grid = drape::test::shuffled_grid(3, 3, 1);
  write_mesh(dir / "keep.glb", grid);
  const auto size_before = fs::file_size(dir / "keep.glb");

  SECTION("a face index out of range") {
    grid.faces(2, 1) = 99;
    for (const char* name : {"keep.glb", "new.obj", "new.ply"}) CHECK_THROWS_AS(write_mesh(dir / name, grid), Error);
  }
  SECTION("a NaN coordinate") {
    grid.vertices(4, 0) = std::nan("");
    for (const char* name : {"keep.glb", "new.obj"}) CHECK_THROWS_AS(write_mesh(dir / name, grid), Error);
  }
  SECTION("glTF cannot keep a vertex that no face uses") {
    grid.vertices.conservativeResize(grid.num_vertices() + 1, 3);
    grid.vertices.bottomRows(1).setConstant(2.0);
    CHECK_THAT(config_error([&] { write_mesh(dir / "keep.glb", grid); }), Catch::Contains("keep.glb") && Catch::Contains("vertex 9"));
    // PLY keeps it.
    write_mesh(dir / "unused.ply", grid);
    CHECK(read_mesh(dir / "unused.ply").num_vertices() == 10);
    fs::remove(dir / "unused.ply");
  }
  CHECK(files_in(dir.path()) == 1);
  CHECK(fs::file_size(dir / "keep.glb") == size_before);
}

TEST_CASE("require_vertex_count names the file and the reason", "[io]") {
  const Mesh grid = drape::test::shuffled_grid(3, 3, 1);
  CHECK_NOTHROW(require_vertex_count(grid, 9, "grid.obj"));
  CHECK_THROWS_MATCHES(require_vertex_count(grid, 6890, "body.obj", "the body model's topology"), ConfigError,
                       Catch::Message("body.obj has 9 vertices, expected 6890 (the body model's topology)"));
  CHECK_THROWS_MATCHES(require_vertex_count(grid, 4, "grid.obj"), ConfigError,
                       Catch::Message("grid.obj has 9 vertices, expected 4"));
}
