// A mesh garment placed for another body or origin is refused at its start
// as a crossing; the refusal names the translation that puts it back around
// the body (separated_start.hpp, clear_offset_hint), and only when that
// translation, dressed as a run's start is, starts clear of the body.
#include <drape/io/mesh_io.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <regex>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string placed_scene_text(const fs::path& file) {
  return "body: {model: parametric}\n"
         "garment: {template: mesh, params: {file: " + file.string() + "}}\n"
         "effects: {gravity: {}, stretching: {}, bending: {}, barrier: {}}\n"
         "solver: {morph_steps: 1, settle_steps: 1, max_newton_iterations: 3}\n";
}

// The refusal of a run of the garment in `file` on the mean body ("" when it
// starts: it takes a step, or part of one, whatever comes of the short run).
std::string start_refusal_of(const fs::path& file) {
  const Simulation sim(test::plugins(), parse_scene(placed_scene_text(file), "placed.yaml"));
  bool started = false;
  SimulationOptions options;
  options.on_step = [&](const SimulationStep&) { started = true; };
  options.on_partial_move = [&](int, int, int, double) { started = true; };
  try {
    sim.run(sim.mean_body(), options);
  } catch (const Error& e) {  // (a blocked morph is an Error of its own: it started)
    return started ? "" : e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a garment placed 20 cm too high is told how far it is displaced", "[garments][fit]") {
  test::TempDir dir;
  // The coarse T-shirt as it starts around the mean body: a garment modelled
  // where it belongs, written out as a user's mesh file.
  const Simulation shirt(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\neffects: [gravity, stretching, barrier]\n"));
  Mesh placed = shirt.garment().mesh;
  write_mesh(dir / "placed.obj", placed);
  CHECK(start_refusal_of(dir / "placed.obj").empty());

  // Exported from a scene whose floor was 20 cm lower: refused as crossing, and told.
  Mesh high = placed;
  high.vertices.col(1).array() += 0.20;
  write_mesh(dir / "high.obj", high);
  const std::string why = start_refusal_of(dir / "high.obj");
  INFO(why);
  CHECK_THAT(why, Catch::Contains("starts crossing the body surface") && Catch::Contains("placed for another body or origin"));
  std::smatch m;
  REQUIRE(std::regex_search(why, m, std::regex("moved about (\\d+) cm down")));
  const int cm = std::stoi(m[1]);
  CHECK(cm >= 17);
  CHECK(cm <= 23);
  // Moved as told, it starts.
  Mesh back = high;
  back.vertices.col(1).array() -= 0.01 * cm;
  write_mesh(dir / "back.obj", back);
  CHECK(start_refusal_of(dir / "back.obj").empty());
}

TEST_CASE("a garment through the body where it belongs is not told it is displaced", "[garments][fit]") {
  test::TempDir dir;
  const Simulation shirt(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                      "effects: [gravity, stretching, barrier]\n"));
  // Its sleeves turned 40 degrees down about the shoulders (a shirt modelled
  // for arms by the sides): through the arms and the trunk, which no
  // translation undoes.
  Mesh arms_down = shirt.garment().mesh;
  const double shoulder_x = 0.17, shoulder_y = arms_down.vertices.col(1).maxCoeff() - 0.08;
  const double turn = 40 * M_PI / 180;
  for (Eigen::Index v = 0; v < arms_down.vertices.rows(); ++v) {
    const double x = arms_down.vertices(v, 0), y = arms_down.vertices(v, 1);
    if (std::abs(x) < shoulder_x) continue;
    const double side = x > 0 ? 1 : -1, dx = std::abs(x) - shoulder_x, dy = y - shoulder_y;
    arms_down.vertices(v, 0) = side * (shoulder_x + dx * std::cos(turn) + dy * std::sin(turn));
    arms_down.vertices(v, 1) = shoulder_y - dx * std::sin(turn) + dy * std::cos(turn);
  }
  write_mesh(dir / "arms_down.obj", arms_down);
  const std::string why = start_refusal_of(dir / "arms_down.obj");
  INFO(why);
  // (Its sleeves lie in the trunk facing away from the way out: placed through the body.)
  CHECK_THAT(why, Catch::Contains("the garment is placed through the body"));
  CHECK_THAT(why, !Catch::Contains("placed for another body"));
}

TEST_CASE("a garment placed through the body is refused before it goes on inside out", "[garments][fit]") {
  test::TempDir dir;
  const Simulation shirt(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                      "effects: [gravity, stretching, barrier]\n"));
  const Mesh placed = shirt.garment().mesh;
  // Its faces wound the other way: the way out is the garment's own (each
  // piece's faces on the whole face away from its centroid), so it starts too.
  Mesh flipped = placed;
  flipped.faces.col(1).swap(flipped.faces.col(2));
  write_mesh(dir / "flipped.obj", flipped);
  CHECK(start_refusal_of(dir / "flipped.obj").empty());

  // Moved 15 cm forward, its back panel lies in the torso, nearer the chest
  // than the back: dressing pushed it out through the chest, and the shirt
  // went on as an apron in front of the body, clear of it, and "settled".
  // Refused, naming the panel, wound either way.
  for (const double forward : {0.15, -0.15}) {
    for (const Mesh* mesh : {&placed, static_cast<const Mesh*>(&flipped)}) {
      Mesh moved = *mesh;
      moved.vertices.col(2).array() += forward;
      write_mesh(dir / "moved.obj", moved);
      const std::string why = start_refusal_of(dir / "moved.obj");
      INFO(forward << (mesh == &flipped ? " flipped: " : ": ") << why);
      CHECK_THAT(why, Catch::Contains("the garment is placed through the body") &&
                          Catch::Contains("with their cloth facing the other way"));
      // The panel named lies in the torso: its vertices' centre within the body's depth.
      std::smatch m;
      REQUIRE(std::regex_search(why, m, std::regex("(\\d+) garment vertices around \\(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\\) m")));
      CHECK(std::stoi(m[1]) >= 50);
      CHECK(std::abs(std::stod(m[4])) < 0.10);
    }
  }

  // Shrunk to half about its centre: inside the torso, its sleeves in the
  // chest. Dressing turned it inside out where it was pushed out through the
  // far side; it settled with its collar 19 cm low. Refused.
  Mesh half = placed;
  const Eigen::RowVector3d centre = half.vertices.colwise().mean();
  half.vertices = ((half.vertices.rowwise() - centre) * 0.5).rowwise() + centre;
  write_mesh(dir / "half.obj", half);
  const std::string why = start_refusal_of(dir / "half.obj");
  INFO(why);
  CHECK_THAT(why, Catch::Contains("the garment is placed through the body"));
}

TEST_CASE("a garment placed beside the body is refused as not going around it", "[garments][fit]") {
  test::TempDir dir;
  const Simulation shirt(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                      "effects: [gravity, stretching, barrier]\n"));
  const Mesh placed = shirt.garment().mesh;
  // Moved 25 cm or more forward, back or aside, both panels lie clear of the
  // torso: dressing and the start checks passed it, and it drapes as an
  // apron. Refused, saying where its cloth lies.
  struct Move {
    int axis;
    double by;
    const char* where;
  };
  for (const Move& m : {Move{2, 0.25, "in front"}, Move{2, 0.40, "in front"}, Move{2, -0.30, "behind"}, Move{0, -0.70, "right"}}) {
    Mesh moved = placed;
    moved.vertices.col(m.axis).array() += m.by;
    write_mesh(dir / "beside.obj", moved);
    const std::string why = start_refusal_of(dir / "beside.obj");
    INFO(m.axis << " by " << m.by << ": " << why);
    CHECK_THAT(why, Catch::Contains("the garment does not go around the body") && Catch::Contains(m.where));
  }
  // Its torso cut away below the armpits, the sleeves left: no loop of it
  // at the chest is a torso's, so nothing is said of going around (a pair
  // of sleeves on their own lies beside the body by design).
  const Mesh& sleeves = placed;
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < sleeves.faces.rows(); ++f) {
    bool arm = true;
    for (int k = 0; k < 3; ++k) arm = arm && std::abs(sleeves.vertices(sleeves.faces(f, k), 0)) > 0.22;
    if (arm) kept.push_back(sleeves.faces.row(f));
  }
  REQUIRE(kept.size() > 20);
  CHECK(garment_beside_body(placed.vertices, placed.faces, shirt.mean_body(), shirt.body_model().faces()).empty());
  Eigen::MatrixX3i arm_faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f) arm_faces.row(static_cast<Eigen::Index>(f)) = kept[f];
  CHECK(garment_beside_body(placed.vertices, arm_faces, shirt.mean_body(), shirt.body_model().faces()).empty());
}

TEST_CASE("a garment turned through the body is told the turn that puts it back", "[garments][fit]") {
  // An outside check: a shirt tilted 20 degrees about x or z, or turned 30
  // about the vertical, was refused as crossing the body with no word of its turn.
  test::TempDir dir;
  const Simulation shirt(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                      "effects: [gravity, stretching, barrier]\n"));
  const Mesh placed = shirt.garment().mesh;
  const Eigen::RowVector3d centre = placed.vertices.colwise().mean();
  struct Turn {
    int axis, degrees;
    const char* told;
  };
  for (const Turn& t : {Turn{0, 20, "turned about 20 degrees clockwise about x"}, Turn{2, -20, "turned about 20 degrees counter-clockwise about z"},
                        Turn{1, 30, "turned about 30 degrees clockwise about y"}}) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(t.degrees * M_PI / 180.0, Eigen::Vector3d::Unit(t.axis)).toRotationMatrix();
    Mesh turned = placed;
    turned.vertices = ((placed.vertices.rowwise() - centre) * turn.transpose()).rowwise() + centre;
    write_mesh(dir / "turned.obj", turned);
    const std::string why = start_refusal_of(dir / "turned.obj");
    INFO(t.axis << " by " << t.degrees << ": " << why);
    CHECK_THAT(why, Catch::Contains(t.told) && Catch::Contains("is it turned?"));
  }
}
