// The `mesh` garment: a user's garment from a file -- here a tube with a sewing
// pattern as UVs, written by the test -- simulated on the parametric body; and
// every kind of bad garment refused with one line naming the file and element.
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "../../framework/src/scene/unsettled.hpp"
#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

// An open tube (a skirt) of `around` x `up` quads around the mean body's
// hips, its UVs the unrolled pattern in metres (test::pattern_tube).
Mesh tube(int around = 24, int up = 6, double r = 0.26, double y0 = 0.92, double y1 = 1.1) {
  return test::pattern_tube(r, y0, y1, around, up);
}

std::string scene_text(const fs::path& file, const std::string& extra = "") {
  return "body: {model: parametric}\n"
         "garment: {template: mesh, params: {file: " + file.string() + extra + "}}\n"
         "effects: {gravity: {}, stretching: {}, bending: {}, barrier: {}}\n"
         "solver: {morph_steps: 2, settle_steps: 6}\n";
}

std::string build_error(const fs::path& file, const std::string& extra = "") {
  return test::message_of([&] { Simulation(test::plugins(), parse_scene(scene_text(file, extra))); });
}

// A file whose first faces are in region 'panel' and the last in 'print',
// simulated with the print as screen-print: both regions, in that order, the
// print the heavier cloth.
void check_panel_and_print(const fs::path& file, int faces) {
  const Simulation sim(test::plugins(), parse_scene(scene_text(file) + "materials: {print: screen-print}\n"));
  const Garment& g = sim.garment();
  REQUIRE(g.materials.size() == 2);
  CHECK(g.materials[0].name == "panel");
  CHECK(g.materials[1].name == "print");
  CHECK(g.materials[1].density > g.materials[0].density);  // the print is the heavier cloth
  CHECK(g.material_of(0) == 0);
  CHECK(g.material_of(faces - 1) == 1);
}

}  // namespace

TEST_CASE("mesh garment: a tube from an OBJ with a UV pattern drapes on the parametric body", "[garments][mesh]") {
  test::TempDir dir;
  const Mesh skirt = tube();
  write_mesh(dir / "skirt.obj", skirt);
  const Simulation sim(test::plugins(), parse_scene(scene_text(dir / "skirt.obj")));
  // Vertex order and count kept; the material space is the pattern.
  REQUIRE(sim.garment().mesh.num_vertices() == skirt.num_vertices());
  CHECK(sim.garment().mesh.uv.isApprox(skirt.uv, 1e-6));
  CHECK(sim.garment().materials.size() == 1);
  CHECK(sim.garment().materials[0].name == "cloth");
  BodyRequest r;
  r.bmi = 28;
  const SimulationResult result = sim.run(sim.body_vertices(sim.shape_for(r)));
  CHECK(result.garment.allFinite());
  CHECK(result.penetration == 0);
  REQUIRE(result.crossings);
  CHECK(result.crossings->total() == 0);
  // It fell under gravity and kept its pattern's size: no edge stretched by more than 20 %.
  CHECK(result.garment.col(1).mean() < skirt.vertices.col(1).mean());
  double worst = 0;
  for (int f = 0; f < skirt.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = skirt.faces(f, k), b = skirt.faces(f, (k + 1) % 3);
      const double rest = (skirt.uv.row(skirt.uv_faces(f, k)) - skirt.uv.row(skirt.uv_faces(f, (k + 1) % 3))).norm();
      worst = std::max(worst, (result.garment.row(a) - result.garment.row(b)).norm() / rest - 1);
    }
  CHECK(worst < 0.2);
}

TEST_CASE("mesh garment: a loose tube slides off the legs and the run says it fell off the body", "[garments][mesh]") {
  // Wider than the legs below the hips: nothing holds it (no friction).
  test::TempDir dir;
  write_mesh(dir / "loose.obj", tube(24, 3, 0.45, 0.30, 0.45));
  const std::string text = "body: {model: parametric}\n"
                           "garment: {template: mesh, params: {file: " + (dir / "loose.obj").string() + "}}\n"
                           "effects: {gravity: {}, stretching: {}, bending: {}, barrier: {}}\n"
                           "solver: {morph_steps: 2, settle_steps: 40}\n";
  const Simulation sim(test::plugins(), parse_scene(text));
  BodyRequest r;
  r.bmi = 28;
  const Eigen::MatrixX3d body = sim.body_vertices(sim.shape_for(r));
  const SimulationResult result = sim.run(body);
  CHECK_FALSE(result.converged);
  // Half of it or more below the soles (a skirt at the ankles, caught on the feet, "settled" with exit 0
  // while all of it had to be: an outside check).
  std::vector<double> heights(result.garment.col(1).data(), result.garment.col(1).data() + result.garment.rows());
  std::sort(heights.begin(), heights.end());
  CHECK(heights[heights.size() / 2] < body.col(1).minCoeff());
  CHECK_THAT(result.unsettled, Catch::Contains("the garment fell off the body: half of it or more"));
  // It stopped once it was off, not after the whole budget.
  CHECK(result.steps < 2 + 40);
}

TEST_CASE("a mesh that passes through itself is refused as the cloth at rest with material_space rest", "[garments][mesh]") {
  // An outside check's mesh crossing itself at 33 edges "settled" at 58 with exit 0: dressing untangles the
  // start, not the cloth's rest shape, and the self-contact leaves pairs near each other at rest alone.
  test::TempDir dir;
  Mesh crossed = tube(24, 3);
  // One vertex of the middle ring pushed through the far wall: its edges pass through the faces there.
  const Eigen::Index v = 24;
  crossed.vertices(v, 0) *= -1.3, crossed.vertices(v, 2) *= -1.3;
  write_mesh(dir / "crossed.obj", crossed);
  const Simulation sim(test::plugins(), parse_scene(scene_text(dir / "crossed.obj", ", material_space: rest")));
  BodyRequest r;
  r.bmi = 25;
  const std::string refused = test::message_of([&] { sim.run(sim.body_vertices(sim.shape_for(r))); });
  CHECK_THAT(refused, Catch::Contains("the garment's mesh passes through itself") &&
                          Catch::Contains("material_space: rest that mesh is the cloth at rest"));
  // Its UVs as the material space: the start is dressed (and untangled) as before, not refused for this.
  const Simulation with_uv(test::plugins(), parse_scene(scene_text(dir / "crossed.obj")));
  CHECK_THAT(test::message_of([&] { with_uv.run(with_uv.body_vertices(with_uv.shape_for(r))); }),
             !Catch::Contains("passes through itself"));
}

TEST_CASE("a garment half below the soles has fallen off though a ring of it is caught on the feet", "[garments][mesh]") {
  Eigen::MatrixX3d body(2, 3), garment(5, 3);
  body << 0, 0.0, 0, 0, 1.7, 0;
  garment << 0, -0.3, 0, 0, -0.2, 0, 0, -0.1, 0, 0, 0.05, 0, 0, 0.08, 0;  // the top two on the feet
  CHECK(scene_detail::fell_off_body(garment, body));
  garment(2, 1) = 0.02;  // three of five above the soles: on the body
  CHECK_FALSE(scene_detail::fell_off_body(garment, body));
}

TEST_CASE("mesh garment: material space from the rest shape needs no UVs", "[garments][mesh]") {
  test::TempDir dir;
  Mesh plain = tube();
  plain.uv.resize(0, 2);
  plain.uv_faces.resize(0, 3);
  write_mesh(dir / "plain.obj", plain);
  CHECK_THAT(build_error(dir / "plain.obj"), Catch::Contains("plain.obj': has no UVs") && Catch::Contains("material_space: rest"));
  const Simulation sim(test::plugins(), parse_scene(scene_text(dir / "plain.obj", ", material_space: rest")));
  // Each rest triangle laid flat: its material-space edges are its 3D edges.
  const Mesh& m = sim.garment().mesh;
  REQUIRE(m.has_uv());
  for (int f = 0; f < m.num_faces(); f += 7)
    for (int k = 0; k < 3; ++k) {
      const double uv = (m.uv.row(m.uv_faces(f, k)) - m.uv.row(m.uv_faces(f, (k + 1) % 3))).norm();
      const double xyz = (plain.vertices.row(plain.faces(f, k)) - plain.vertices.row(plain.faces(f, (k + 1) % 3))).norm();
      CHECK(uv == Approx(xyz).epsilon(1e-9));
    }
}

TEST_CASE("mesh garment: bad garments are refused naming the file and the element", "[garments][mesh]") {
  test::TempDir dir;
  SECTION("a seam exported with split vertices: refused, or welded on request") {
    Mesh split = tube();
    // Vertex 0's faces get a copy of it appended at the end.
    const int copy = split.num_vertices();
    split.vertices.conservativeResize(copy + 1, 3);
    split.vertices.row(copy) = split.vertices.row(0);
    for (int f = 0; f < split.num_faces(); f += 2)
      for (int k = 0; k < 3; ++k)
        if (split.faces(f, k) == 0) split.faces(f, k) = copy;
    // The same as a PLY (read through assimp, which welded it without a
    // word and renumbered every vertex after it). (Not as a glTF: assimp's
    // exporter joins it on writing, assimp_mesh_writer.cpp.)
    for (const std::string name : {"split.obj", "split.ply"}) {
      write_mesh(dir / name, split);
      CHECK_THAT(build_error(dir / name), Catch::Contains(name + "': 1 vertices duplicate an earlier one (vertex " + std::to_string(copy) +
                                                          " (from 0: the file's vertex " + std::to_string(copy + 1) +
                                                          ") sits on vertex 0 (from 0: the file's vertex 1))"));
      // Placed at the scene's line that names the file (a garment's build named no scene line: an outside check).
      CHECK_THAT(build_error(dir / name), Catch::StartsWith("<scene>:2: "));
      const Simulation sim(test::plugins(), parse_scene(scene_text(dir / name, ", weld: true")));
      CHECK(sim.garment().mesh.num_vertices() == copy);
    }
    // The copy a few microns off (an exporter's rounding): the same seam, not an opening the garment falls
    // through (an outside check's copies 5-20 um apart were taken as an open seam and the skirt fell off).
    split.vertices(copy, 0) += 2e-5;
    write_mesh(dir / "near.obj", split);
    CHECK_THAT(build_error(dir / "near.obj"), Catch::Contains("1 vertices duplicate an earlier one (vertex " + std::to_string(copy) +
                                                              " (from 0: the file's vertex " + std::to_string(copy + 1) +
                                                              ") sits on vertex 0 (from 0: the file's vertex 1), 20 um from it"));
    const Simulation welded(test::plugins(), parse_scene(scene_text(dir / "near.obj", ", weld: true")));
    CHECK(welded.garment().mesh.num_vertices() == copy);
  }
  SECTION("a short edge is no seam") {
    // Two vertices of one edge a hair apart are a short edge, never a seam's copies (welding them
    // collapsed its faces: "face uses a vertex twice").
    Mesh short_edge = tube();
    const Eigen::RowVector3d mid = 0.5 * (short_edge.vertices.row(0) + short_edge.vertices.row(1));
    short_edge.vertices.row(1) = mid + 1e-5 * (short_edge.vertices.row(1) - mid).normalized();
    short_edge.vertices.row(0) = mid - 1e-5 * (short_edge.vertices.row(1) - mid).normalized();
    write_mesh(dir / "short.obj", short_edge);
    CHECK_THAT(build_error(dir / "short.obj"), !Catch::Contains("duplicate an earlier one"));
    // Within the weld distance (1 nm, an outside check's): an edge collapsed in 3D, not a seam either (it was
    // "duplicate ... both on the border", and weld: true then made a face use a vertex twice). Its rest shape
    // comes from the UVs, where it is whole: the garment is built, welded or not, with every vertex.
    short_edge.vertices.row(0) = mid - 5e-10 * (short_edge.vertices.row(1) - mid).normalized();
    short_edge.vertices.row(1) = mid + 5e-10 * (short_edge.vertices.row(1) - mid).normalized();
    write_mesh(dir / "collapsed.obj", short_edge);
    CHECK_THAT(build_error(dir / "collapsed.obj"), !Catch::Contains("duplicate an earlier one"));
    const Simulation welded(test::plugins(), parse_scene(scene_text(dir / "collapsed.obj", ", weld: true")));
    CHECK(welded.garment().mesh.num_vertices() == short_edge.num_vertices());
  }
  SECTION("an edge of three faces") {
    Mesh fin = tube();
    const int n = fin.num_vertices();
    fin.vertices.conservativeResize(n + 1, 3);
    fin.vertices.row(n) << 0.0, 1.3, 0.6;
    fin.faces.conservativeResize(fin.num_faces() + 1, 3);
    // Along face 0's edge b-d, which faces 0 and 3 already share.
    fin.faces.row(fin.num_faces() - 1) << fin.faces(0, 1), fin.faces(0, 2), n;
    fin.uv_faces.conservativeResize(fin.faces.rows(), 3);
    fin.uv_faces.row(fin.faces.rows() - 1) << 0, 1, 30;
    write_mesh(dir / "fin.obj", fin);
    CHECK_THAT(build_error(dir / "fin.obj"), Catch::Contains("fin.obj': the edge between vertex ") && Catch::Contains("(from 0: the file's vertex") && Catch::Contains("non-manifold"));
  }
  SECTION("a degenerate UV triangle") {
    Mesh flat = tube();
    flat.uv.row(flat.uv_faces(5, 2)) = flat.uv.row(flat.uv_faces(5, 0));
    write_mesh(dir / "flat.obj", flat);
    CHECK_THAT(build_error(dir / "flat.obj"), Catch::Contains("flat.obj': face ") && Catch::Contains("(from 0: the file's triangle ") && Catch::Contains("degenerate in material space"));
  }
  SECTION("a vertex no face uses") {
    Mesh loose = tube();
    const int n = loose.num_vertices();
    loose.vertices.conservativeResize(n + 1, 3);
    loose.vertices.row(n) << 0.0, 1.3, 1.5;  // 1.5 m in front of the body, where nothing would move it
    write_mesh(dir / "loose.obj", loose);
    CHECK_THAT(build_error(dir / "loose.obj"), Catch::Contains("loose.obj': vertex " + std::to_string(n) + " (from 0: the file's vertex " +
                                                               std::to_string(n + 1) + ") (at 0.000, 1.300, 1.500) is used by no face (1 such vertex)"));
  }
  SECTION("a sliver of the rest shape: its area in figures, and no advice to use the material space in use") {
    Mesh sliver = tube();
    // Face 5's third corner onto the middle of its first edge, a micrometre off it.
    const Eigen::RowVector3d a = sliver.vertices.row(sliver.faces(5, 0)), b = sliver.vertices.row(sliver.faces(5, 1));
    sliver.vertices.row(sliver.faces(5, 2)) = 0.5 * (a + b) + Eigen::RowVector3d(0, 1e-6, 0);
    write_mesh(dir / "sliver.obj", sliver);
    const std::string why = build_error(dir / "sliver.obj", ", material_space: rest");
    INFO(why);
    CHECK_THAT(why, Catch::Contains("degenerate in material space (its rest triangle has area ") &&
                        Catch::Contains("e-0") && Catch::Contains("collapse or remesh it") &&
                        !Catch::Contains("use material_space: rest") && !Catch::Contains("area 0.000000"));
  }
  SECTION("a material space it does not know, and a scale out of range") {
    write_mesh(dir / "skirt.obj", tube());
    CHECK_THAT(build_error(dir / "skirt.obj", ", material_space: sideways"), Catch::Contains("material_space") && Catch::Contains("uv"));
    CHECK_THAT(build_error(dir / "skirt.obj", ", uv_scale: 0"), Catch::Contains("uv_scale"));
  }
  SECTION("a garment in other units, or modelled away from the body") {
    // The tube in centimetres and in millimetres: the error says the scale that would fit.
    for (const auto& [factor, scale] : {std::pair{100.0, "scaled by 0.01"}, std::pair{1000.0, "scaled by 0.001"}}) {
      Mesh big = tube();
      big.vertices *= factor;
      write_mesh(dir / "big.obj", big);
      CHECK_THAT(build_error(dir / "big.obj"), Catch::Contains("big.obj)") && Catch::Contains("drape reads metres") &&
                                                   Catch::Contains(scale));
    }
    // Two metres to the side, and Z up (lying at the body's feet): not around the body.
    Mesh aside = tube();
    aside.vertices.col(0).array() += 2.0;
    write_mesh(dir / "aside.obj", aside);
    CHECK_THAT(build_error(dir / "aside.obj"), Catch::Contains("away from the body") && Catch::Contains("Y up, metres"));
    Mesh z_up = tube();
    z_up.vertices.col(1).swap(z_up.vertices.col(2));
    z_up.vertices.col(1) *= -1.0;
    write_mesh(dir / "zup.obj", z_up);
    CHECK_THAT(build_error(dir / "zup.obj"), Catch::Contains("away from the body"));
  }
  SECTION("a missing file, and none given") {
    CHECK_THAT(build_error(dir / "nowhere.obj"), Catch::Contains("nowhere.obj': no such file"));
    CHECK_THAT(test::message_of([&] {
                 Simulation(test::plugins(), parse_scene("body: {model: parametric}\ngarment: {template: mesh}\neffects: [gravity]\n"));
               }),
               Catch::Contains("garment mesh: give the file"));
  }
}

TEST_CASE("mesh garment: drape assets builds its correspondences, hierarchy and eigenbasis", "[garments][mesh][cli]") {
  test::TempDir dir;
  write_mesh(dir / "skirt.obj", tube());
  std::string out;
  REQUIRE(test::run(test::drape_program().string() + " assets --garment mesh --garment-param file=" +
                        (dir / "skirt.obj").string() + " --k 20 --no-cache",
                    out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("garment  mesh: 168 vertices, 288 faces"));
  CHECK_THAT(out, Catch::Contains("spectral: k = 20"));
  CHECK(test::run(test::drape_program().string() + " assets --garment mesh --garment-param file", out) == 2);
  CHECK_THAT(out, Catch::Contains("--garment-param wants name=value"));
}

TEST_CASE("mesh garment: an OBJ's usemtl groups are material regions the scene names", "[garments][mesh]") {
  test::TempDir dir;
  const Mesh skirt = tube();
  write_mesh(dir / "plain.obj", skirt);
  // The same file with the first half of its faces in 'panel' and the rest in 'print'.
  std::ifstream in(dir / "plain.obj");
  std::ofstream out(dir / "regions.obj");
  int faces = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("f ", 0) == 0) {
      if (faces == 0) out << "usemtl panel\n";
      if (faces == skirt.num_faces() / 2) out << "usemtl print\n";
      ++faces;
    }
    out << line << "\n";
  }
  out.close();
  check_panel_and_print(dir / "regions.obj", skirt.num_faces());
  CHECK_THAT(test::message_of([&] { Simulation(test::plugins(), parse_scene(scene_text(dir / "regions.obj") + "materials: {sleeve: screen-print}\n")); }),
             Catch::Contains("has no region 'sleeve'") && Catch::Contains("panel, print"));
}

namespace {

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    unsigned n = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    // Output character k carries bits of input byte k - 1 (k >= 1); past the end, '='.
    for (int k = 0; k < 4; ++k) out += (k < 2 || i + k - 1 < bytes.size()) ? digits[(n >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

template <class T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// The mesh as a glTF 2.0 file written by hand (not through drape's or
// assimp's writer): one vertex per distinct (position, UV) corner, and one
// primitive per run of faces with the same material, named as given.
void write_gltf_by_hand(const fs::path& file, const Mesh& m, const std::vector<std::pair<std::string, int>>& runs) {
  std::vector<std::pair<int, int>> corners;  // (vertex, uv) of each glTF vertex
  std::vector<std::uint32_t> index;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> c{m.faces(f, k), m.uv_faces(f, k)};
      auto it = std::find(corners.begin(), corners.end(), c);
      if (it == corners.end()) it = corners.insert(corners.end(), c);
      index.push_back(static_cast<std::uint32_t>(it - corners.begin()));
    }
  std::string bin;
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = -lo;
  for (const auto& [v, t] : corners) {
    const Eigen::Vector3f p = m.vertices.row(v).transpose().cast<float>();
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (int k = 0; k < 3; ++k) append(bin, p[k]);
  }
  const std::size_t uv_at = bin.size();
  for (const auto& [v, t] : corners)
    for (int k = 0; k < 2; ++k) append(bin, static_cast<float>(m.uv(t, k)));
  std::ostringstream views, accessors, primitives, materials;
  const std::size_t n = corners.size();
  views << "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" << uv_at << "},{\"buffer\":0,\"byteOffset\":" << uv_at
        << ",\"byteLength\":" << 8 * n << "}";
  accessors << "{\"bufferView\":0,\"componentType\":5126,\"count\":" << n << ",\"type\":\"VEC3\",\"min\":[" << lo[0] << ","
            << lo[1] << "," << lo[2] << "],\"max\":[" << hi[0] << "," << hi[1] << "," << hi[2] << "]},"
            << "{\"bufferView\":1,\"componentType\":5126,\"count\":" << n << ",\"type\":\"VEC2\"}";
  int face = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::size_t at = bin.size();
    for (int f = face; f < face + runs[r].second; ++f)
      for (int k = 0; k < 3; ++k) append(bin, index[static_cast<std::size_t>(3 * f + k)]);
    face += runs[r].second;
    views << ",{\"buffer\":0,\"byteOffset\":" << at << ",\"byteLength\":" << bin.size() - at << "}";
    accessors << ",{\"bufferView\":" << r + 2 << ",\"componentType\":5125,\"count\":" << 3 * runs[r].second
              << ",\"type\":\"SCALAR\"}";
    primitives << (r ? "," : "") << "{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"indices\":" << r + 2
               << ",\"material\":" << r << "}";
    materials << (r ? "," : "") << "{\"name\":\"" << runs[r].first << "\"}";
  }
  std::ofstream out(file);
  out << "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
      << "\"meshes\":[{\"primitives\":[" << primitives.str() << "]}],\"materials\":[" << materials.str() << "],"
      << "\"buffers\":[{\"byteLength\":" << bin.size() << ",\"uri\":\"data:application/octet-stream;base64,"
      << base64(bin) << "\"}],\"bufferViews\":[" << views.str() << "],\"accessors\":[" << accessors.str() << "]}\n";
}

}  // namespace

TEST_CASE("mesh garment: a glTF's materials are material regions the scene names", "[garments][mesh]") {
  test::TempDir dir;
  const Mesh skirt = tube();
  const int half = skirt.num_faces() / 2;
  write_gltf_by_hand(dir / "regions.gltf", skirt, {{"panel", half}, {"print", skirt.num_faces() - half}});
  // The reader: the tube's vertices (seam corners merged back), its faces in order, each face's material.
  const MaterialMesh read = read_mesh_with_materials(dir / "regions.gltf");
  CHECK(read.mesh.num_vertices() == skirt.num_vertices());
  REQUIRE(read.mesh.num_faces() == skirt.num_faces());
  CHECK(read.material_names == std::vector<std::string>{"panel", "print"});
  REQUIRE(read.face_material.size() == static_cast<std::size_t>(skirt.num_faces()));
  for (int f = 0; f < skirt.num_faces(); ++f) CHECK(read.face_material[static_cast<std::size_t>(f)] == (f < half ? 0 : 1));
  for (int f = 0; f < skirt.num_faces(); f += 17)
    for (int k = 0; k < 3; ++k)
      CHECK((read.mesh.vertices.row(read.mesh.faces(f, k)) - skirt.vertices.row(skirt.faces(f, k))).norm() < 1e-6);

  check_panel_and_print(dir / "regions.gltf", skirt.num_faces());
  // A PLY carries no materials: one region, "cloth".
  write_mesh(dir / "plain.ply", skirt);
  const MaterialMesh ply = read_mesh_with_materials(dir / "plain.ply");
  CHECK(ply.material_names.size() == 1);
  CHECK(ply.face_material.size() == static_cast<std::size_t>(skirt.num_faces()));
  const Simulation plain(test::plugins(), parse_scene(scene_text(dir / "plain.ply", ", material_space: rest")));
  REQUIRE(plain.garment().materials.size() == 1);
  CHECK(plain.garment().materials[0].name == "cloth");
}

// `drape experiment` on a user's garment: a table of two models trained on
// drapes of the tube, every column filled (nothing assumes the T-shirt).
TEST_CASE("mesh garment: drape experiment trains and tabulates models of it", "[garments][mesh][cli]") {
  test::TempDir dir;
  write_mesh(dir / "skirt.obj", tube());
  {
    std::ofstream scene(dir / "skirt.yaml");
    scene << scene_text(dir / "skirt.obj");
    std::ofstream experiment(dir / "skirt_models.yaml");
    experiment << "name: skirt_models\n"
               << "title: \"A user's skirt\"\n"
               << "datasets:\n  regular: {scene: skirt.yaml, count: 10, bmi: \"20:28\", seed: 1}\n"
               << "training: {epochs: 2, batch: 4, lr: 1.0e-3, schedule: cosine, patience: 5, seed: 0}\n"
               << "columns: [ME, L_l, L_e, L_s, L_d, p, train_h, infer]\n"
               << "rows:\n"
               << "  - {name: CNN, train: " << (test::source_dir() / "graphs/drape.yaml").string() << "}\n"
               << "  - {name: MLP, train: " << (test::source_dir() / "graphs/baselines/mlp_l2.yaml").string() << "}\n";
  }
  std::string out;
  const int status = test::run(test::drape_program().string() + " experiment " + (dir / "skirt_models.yaml").string() +
                                   " --threads 1 --work " + (dir / "run").string() + " --data-dir " + (dir / "data").string(),
                               out);
  INFO(out);
  REQUIRE(status == 0);
  std::ifstream table(dir / "run/table.md");
  const std::string text((std::istreambuf_iterator<char>(table)), std::istreambuf_iterator<char>());
  for (const char* row : {"| CNN |", "| MLP |"}) {
    const auto at = text.find(row);
    REQUIRE(at != std::string::npos);
    const std::string line = text.substr(at, text.find('\n', at) - at);
    INFO(line);
    CHECK(std::count(line.begin(), line.end(), '|') == 10);  // the row name and 8 columns
    CHECK(line.find("nan") == std::string::npos);
    CHECK(line.find(" ms") != std::string::npos);  // inference measured
  }
}
