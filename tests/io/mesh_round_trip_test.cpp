// Vertex order and count are the identity of a fixed-topology mesh: every
// format must give them back unchanged. The shuffled grid makes any reordering
// by assimp (measured: none for PLY and glTF when reading with no
// post-processing) show up here.
#include <drape/io/mesh_io.hpp>

#include "mesh_test_util.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <iterator>

using namespace drape;
using drape::test::TempDir;

namespace {

// Float precision relative to the mesh size: the binary formats store floats.
constexpr double kFloatTolerance = 1e-6;

// The UV seen at every face corner, which is what must survive (the uv table
// itself may be laid out differently by PLY and glTF).
Eigen::MatrixXd corner_uvs(const Mesh& m) {
  Eigen::MatrixXd out(m.num_faces() * 3, 2);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.row(3 * f + k) = m.uv.row(m.uv_faces(f, k));
  return out;
}

void require_same_geometry(const Mesh& read, const Mesh& written, double tolerance) {
  REQUIRE(read.num_vertices() == written.num_vertices());
  REQUIRE(read.num_faces() == written.num_faces());
  CHECK((read.vertices - written.vertices).cwiseAbs().maxCoeff() <= tolerance);
  CHECK(read.faces == written.faces);
}

}  // namespace

TEST_CASE("every format keeps a shuffled mesh's vertex order, positions, faces and corner UVs", "[io]") {
  TempDir dir;
  const Mesh grid = drape::test::shuffled_grid(9, 7, 42);
  for (const char* name : {"grid.obj", "grid.ply", "grid.gltf", "grid.glb"}) {
    SECTION(name) {
      write_mesh(dir / name, grid);
      const Mesh back = read_mesh(dir / name);
      const bool obj = std::string(name).ends_with(".obj");
      require_same_geometry(back, grid, obj ? 0.0 : kFloatTolerance);
      REQUIRE(back.has_uv());
      CHECK((corner_uvs(back) - corner_uvs(grid)).cwiseAbs().maxCoeff() <= (obj ? 0.0 : kFloatTolerance));
    }
  }
}

TEST_CASE("a mesh without UVs round-trips without UVs", "[io]") {
  TempDir dir;
  Mesh grid = drape::test::shuffled_grid(5, 4, 7);
  grid.uv.resize(0, 2);
  grid.uv_faces.resize(0, 3);
  for (const char* name : {"plain.obj", "plain.ply", "plain.glb"}) {
    SECTION(name) {
      write_mesh(dir / name, grid);
      const Mesh back = read_mesh(dir / name);
      require_same_geometry(back, grid, kFloatTolerance);
      CHECK_FALSE(back.has_uv());
    }
  }
}

TEST_CASE("quads are split into a fan that keeps the corner order", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "cube.obj", drape::test::cube_obj());
  const Mesh cube = read_mesh(dir / "cube.obj");
  REQUIRE(cube.num_vertices() == 8);
  REQUIRE(cube.num_faces() == 12);
  // front quad 1 2 3 4 -> (0,1,2) (0,2,3); bottom quad 5 6 2 1 -> (4,5,1) (4,1,0)
  CHECK(cube.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(cube.faces.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(cube.faces.row(10) == Eigen::RowVector3i(4, 5, 1));
  CHECK(cube.faces.row(11) == Eigen::RowVector3i(4, 1, 0));
  CHECK(cube.uv_faces.row(11) == Eigen::RowVector3i(13, 1, 0));
}

TEST_CASE("a polygon whose first corners lie on a line is split from a corner that leaves no triangle flat", "[io]") {
  // An outside check: a convex hexagon whose first three corners lie on one row (of the mesh and of the UVs)
  // was fanned from corner 1 into a triangle of no area and refused as "face 0 is degenerate".
  TempDir dir;
  drape::test::write_text(dir / "hex.obj",
                          "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 0 1 0\n"
                          "vt 0 0\nvt 0.5 0\nvt 1 0\nvt 1 1\nvt 0.5 1\nvt 0 1\n"
                          "f 1/1 2/2 3/3 4/4 5/5 6/6\n");
  const Mesh hex = read_mesh(dir / "hex.obj");
  REQUIRE(hex.num_faces() == 4);
  double area = 0;
  for (Eigen::Index f = 0; f < hex.num_faces(); ++f) {
    const Eigen::Vector3d a = hex.vertices.row(hex.faces(f, 0)), b = hex.vertices.row(hex.faces(f, 1)),
                          c = hex.vertices.row(hex.faces(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    CHECK(n.norm() > 1e-6);  // no flat triangle
    CHECK(n.z() > 0);        // the polygon's orientation kept
    area += 0.5 * n.norm();
    const Eigen::Vector2d ua = hex.uv.row(hex.uv_faces(f, 0)), ub = hex.uv.row(hex.uv_faces(f, 1)), uc = hex.uv.row(hex.uv_faces(f, 2));
    CHECK(std::abs((ub - ua).x() * (uc - ua).y() - (ub - ua).y() * (uc - ua).x()) > 1e-6);
  }
  CHECK(area == Approx(2.0));  // the whole hexagon, once
}

TEST_CASE("a cube with UV seams stays 8 vertices in every format", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "cube.obj", drape::test::cube_obj());
  const Mesh cube = read_mesh(dir / "cube.obj");
  REQUIRE(cube.uv.rows() == 14);

  SECTION("OBJ keeps the 14 per-corner UVs exactly") {
    write_mesh(dir / "again.obj", cube);
    const Mesh back = read_mesh(dir / "again.obj");
    require_same_geometry(back, cube, 0.0);
    CHECK(back.uv == cube.uv);
    CHECK(back.uv_faces == cube.uv_faces);
  }
  for (const char* name : {"cube.ply", "cube.gltf", "cube.glb"}) {
    SECTION(name) {
      write_mesh(dir / name, cube);
      const Mesh back = read_mesh(dir / name);
      require_same_geometry(back, cube, kFloatTolerance);
      // The seam copies came back as extra UV rows, not as extra vertices.
      CHECK(back.uv.rows() == 14);
      CHECK((corner_uvs(back) - corner_uvs(cube)).cwiseAbs().maxCoeff() <= kFloatTolerance);
    }
  }
}

TEST_CASE("OBJ polygons keep their groups", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "cube.obj", drape::test::cube_obj());
  const PolygonMesh cube = read_obj_polygons(dir / "cube.obj");
  REQUIRE(cube.num_faces() == 6);
  CHECK(cube.face_size(5) == 4);
  CHECK(cube.group_names == std::vector<std::string>{"sides", "caps"});
  CHECK(cube.face_group == std::vector<int>{0, 0, 0, 0, 1, 1});
  CHECK(group_vertices(cube, "caps", "cube.obj") == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7});
  CHECK(group_vertices(cube, "sides", "cube.obj").size() == 8);
  CHECK_THROWS_WITH(group_vertices(cube, "cap", "cube.obj"), Catch::Contains("no group 'cap'") && Catch::Contains("caps"));
}

TEST_CASE("OBJ details: negative indices, v//vn corners, comments, CRLF, unused vertices", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "t.obj",
                          "v 0 0 0\r\nv 1 0 0 # trailing comment\r\nv 0 1 0\r\nv 5 5 5\r\nvn 0 0 1\r\n"
                          "f 1//1 2//1 3//1\r\nf -4 -3 -2\r\n");
  const Mesh m = read_mesh(dir / "t.obj");
  CHECK(m.num_vertices() == 4);  // vertex 4 is used by no face but keeps its place
  REQUIRE(m.num_faces() == 2);
  CHECK(m.faces.row(1) == Eigen::RowVector3i(0, 1, 2));
  CHECK_FALSE(m.has_uv());
  CHECK(m.vertices(3, 2) == 5.0);
}

TEST_CASE("an OBJ that starts with a byte-order mark keeps its first vertex and a face index 0 is named", "[io]") {
  // The mark made the first statement's keyword unknown: the first vertex was
  // dropped without a word (an outside check's body read 6,903 of 6,904).
  TempDir dir;
  drape::test::write_text(dir / "bom.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Mesh m = read_mesh(dir / "bom.obj");
  REQUIRE(m.num_vertices() == 3);
  CHECK(m.vertices.row(1) == Eigen::RowVector3d(1, 0, 0));
  CHECK(m.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  drape::test::write_text(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  CHECK_THROWS_WITH(read_mesh(dir / "zero.obj"), Catch::Contains("zero.obj:4") && Catch::Contains("they count from 1"));
}

TEST_CASE("a PLY written in double is read in double in ASCII and both byte orders", "[io]") {
  // assimp keeps positions in float: a body written in double was read
  // rounded by 6e-8 m, and a simulated drape on it moved by up to 7.5 mm
  // (an outside check). Coordinates a float cannot hold, a property after
  // them and an element before the vertices.
  const double v[3][3] = {{0.1234567890123, 1.0000000001, 0.3}, {1.1, 0.2000000000007, 0.3}, {0.5, 1.3, 0.7000000000009}};
  TempDir dir;
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    INFO(format);
    const bool ascii = format == "ascii";
    std::string ply = "ply\nformat " + format + " 1.0\nelement vertex 3\n"
                      "property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const bool big = format == "binary_big_endian";
    auto put = [&](const void* data, std::size_t size) {
      std::string bytes(static_cast<const char*>(data), size);
      if (big) std::reverse(bytes.begin(), bytes.end());
      ply += bytes;
    };
    if (ascii) {
      char line[128];
      for (const auto& p : v) std::snprintf(line, sizeof line, "%.17g %.17g %.17g 7\n", p[0], p[1], p[2]), ply += line;
      ply += "3 0 1 2\n";
    } else {
      for (const auto& p : v) {
        for (const double c : p) put(&c, 8);
        ply += '\x07';
      }
      ply += '\x03';
      for (const int i : {0, 1, 2}) put(&i, 4);
    }
    drape::test::write_text(dir / "d.ply", ply);
    const Mesh m = read_mesh(dir / "d.ply");
    REQUIRE(m.num_vertices() == 3);
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) CHECK(m.vertices(i, c) == v[i][c]);
    CHECK(m.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  }
  // assimp reads a file's first data as its vertices: a camera element
  // before them was read as a vertex, and no faces, without a word.
  const std::string header = "element camera 1\nproperty float zoom\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  drape::test::write_text(dir / "camera.ply", "ply\nformat ascii 1.0\n" + header + "2.5\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK_THROWS_WITH(read_mesh(dir / "camera.ply"), Catch::Contains("the element 'camera' comes before the vertices"));
  std::string binary = "ply\nformat binary_little_endian 1.0\n" + header;
  const float data[10] = {2.5f, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  binary += std::string(reinterpret_cast<const char*>(data), sizeof data) + '\x03';
  for (const int i : {0, 1, 2}) binary += std::string(reinterpret_cast<const char*>(&i), 4);
  drape::test::write_text(dir / "camera_binary.ply", binary);
  CHECK_THROWS_WITH(read_mesh(dir / "camera_binary.ply"), Catch::Contains("the element 'camera' comes before the vertices"));
}

// An ASCII PLY header: float x y z (and s t with `uv`) per vertex, a list of int corners per face.
static std::string ascii_ply_header(int vertices, int faces, bool uv = false) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\n" +
         (uv ? "property float s\nproperty float t\n" : "") + "element face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST_CASE("a triangle soup read through assimp is merged back in first-occurrence order", "[io]") {
  TempDir dir;
  // Two triangles sharing an edge, written with one vertex per corner.
  drape::test::write_text(dir / "soup.ply", ascii_ply_header(6, 2) + "0 0 0\n1 0 0\n1 1 0\n0 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 3 4 5\n");
  const Mesh m = read_mesh(dir / "soup.ply");
  REQUIRE(m.num_vertices() == 4);
  CHECK(m.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(m.faces.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(m.vertices.row(3) == Eigen::RowVector3d(0, 1, 0));
}

TEST_CASE("a PLY vertex at the same place as another is a vertex of its own unless it is a copy", "[io]") {
  // An outside check: a body PLY of 6,904 vertices two of which coincide was
  // read as 6,903, and a garment PLY with one vertex split in two was read
  // renumbered from it on, where its OBJ is refused by the mesh garment.
  TempDir dir;
  // Two triangles sharing an edge, and vertex 4 where vertex 1 is (a third triangle uses it).
  drape::test::write_text(dir / "twin.ply", ascii_ply_header(5, 3) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 0 0\n3 0 1 2\n3 0 2 3\n3 4 2 0\n");
  const Mesh twin = read_mesh(dir / "twin.ply");
  REQUIRE(twin.num_vertices() == 5);
  CHECK(twin.faces.row(2) == Eigen::RowVector3i(4, 2, 0));
  // With texture coordinates: the copy with another UV is a seam copy, merged;
  // one with the same UV a vertex of its own.
  const std::string header = ascii_ply_header(5, 3, true);
  const std::string faces = "3 0 1 2\n3 0 2 3\n3 4 2 0\n";
  drape::test::write_text(dir / "seam.ply", header + "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n1 0 0 0.5 0\n" + faces);
  const Mesh seam = read_mesh(dir / "seam.ply");
  CHECK(seam.num_vertices() == 4);
  CHECK(seam.faces.row(2) == Eigen::RowVector3i(1, 2, 0));
  drape::test::write_text(dir / "same_uv.ply", header + "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n1 0 0 1 0\n" + faces);
  CHECK(read_mesh(dir / "same_uv.ply").num_vertices() == 5);
}

TEST_CASE("a PLY with a quad and an unused vertex keeps the vertex and fans the quad", "[io]") {
  TempDir dir;
  drape::test::write_text(dir / "quad.ply",
                          "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "9 9 9\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 1 2 3 4\n");
  const Mesh m = read_mesh(dir / "quad.ply");
  REQUIRE(m.num_vertices() == 5);
  CHECK(m.vertices.row(0) == Eigen::RowVector3d(9, 9, 9));
  REQUIRE(m.num_faces() == 2);
  CHECK(m.faces.row(0) == Eigen::RowVector3i(1, 2, 3));
  CHECK(m.faces.row(1) == Eigen::RowVector3i(1, 3, 4));
}

TEST_CASE("a glTF node's transform places its mesh, as every viewer shows it", "[io]") {
  // An outside check: node transforms were ignored, so a garment in
  // centimetres scaled to metres by its node was refused as 82 m across,
  // and one its node moved 2 m aside was draped on the body as if not moved.
  TempDir dir;
  const Mesh grid = drape::test::shuffled_grid(4, 4, 3);
  write_mesh(dir / "plain.gltf", grid);
  std::ifstream in(dir / "plain.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string node = "\"mesh\": 0";
  const std::size_t at = text.find(node);
  REQUIRE(at != std::string::npos);
  const auto with_node = [&](const std::string& transform) {
    std::string moved = text;
    moved.replace(at, node.size(), node + ", " + transform);
    return moved;
  };
  drape::test::write_text(dir / "moved.gltf", with_node("\"translation\": [2.0, 0.5, -1.0], \"scale\": [0.01, 0.01, 0.01]"));
  const Mesh plain = read_mesh(dir / "plain.gltf"), moved = read_mesh(dir / "moved.gltf");
  REQUIRE(moved.num_vertices() == plain.num_vertices());
  CHECK(moved.faces == plain.faces);
  const Eigen::MatrixX3d expected = (plain.vertices * 0.01).rowwise() + Eigen::RowVector3d(2.0, 0.5, -1.0);
  CHECK((moved.vertices - expected).cwiseAbs().maxCoeff() < 1e-6);
}
