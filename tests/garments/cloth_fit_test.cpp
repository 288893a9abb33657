// What a garment's cloth measures around at rest, and the two refusals built
// on it: a garment whose cloth cannot go around the body it is put on
// (refused before any work, with the uv_scale that fits), and a morph the
// contact cannot finish (said in words: too small, or what else holds the
// cloth back). The loops' lengths are checked against the unrolled pattern
// by hand; the refusals against garments made small in their pattern only,
// in their shape only, or in both.
#include <drape/geometry/girth.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/materials/materials.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/scene_body.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "../../framework/src/scene/cloth_fit.hpp"
#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

// A tube about the y axis whose pattern is `pattern` times its own unrolled
// length (test::pattern_tube).
Mesh fit_tube(double r, double y0, double y1, double pattern = 1.0, int around = 32, int up = 8) {
  return test::pattern_tube(r, y0, y1, around, up, pattern);
}

std::string fit_scene_text(const fs::path& file, const std::string& extra = "", const std::string& params = "") {
  return "body: {model: parametric}\n"
         "garment: {template: mesh, params: {file: " + file.string() + params + "}}\n"
         "effects: {gravity: {}, stretching: {}, bending: {}, barrier: {}}\n"
         "solver: {morph_steps: 2, settle_steps: 2}\n" + extra;
}

}  // namespace

TEST_CASE("girth: a loop's material length is the pattern's, whatever the 3D shape", "[geometry][girth]") {
  const double r = 0.3;
  const int around = 32;
  const double chords = 2 * around * r * std::sin(M_PI / around);  // the 3D loop, by hand
  for (const double pattern : {1.0, 0.7}) {
    const Mesh m = fit_tube(r, 0.0, 1.0, pattern, around);
    const geometry::Girth g = geometry::horizontal_girth(m.vertices, m.faces, 0.43, {0, 0}, &m.uv, &m.uv_faces);
    REQUIRE(g.found);
    CHECK(g.length == Approx(chords).epsilon(1e-9));
    CHECK(g.material_length == Approx(pattern * 2 * M_PI * r).epsilon(1e-9));  // the unrolled pattern
  }
  // Shrunk in 3D (a full pattern crumpled smaller): the material length stays.
  Mesh small = fit_tube(r, 0.0, 1.0);
  small.vertices.col(0) *= 0.5;
  small.vertices.col(2) *= 0.5;
  const geometry::Girth g = geometry::horizontal_girth(small.vertices, small.faces, 0.43, {0, 0}, &small.uv, &small.uv_faces);
  CHECK(g.length == Approx(0.5 * chords).epsilon(1e-9));
  CHECK(g.material_length == Approx(2 * M_PI * r).epsilon(1e-9));
  // Without a material space: 0.
  CHECK(geometry::horizontal_girth(small.vertices, small.faces, 0.43, {0, 0}).material_length == 0.0);
}

TEST_CASE("a garment whose cloth is cut too small to go around the body is refused before any work", "[garments][fit]") {
  test::TempDir dir;
  // A tube about the mean body's chest (its band: 58-72 % of 1.75 m), 1.76 m
  // around in 3D, clear of the torso.
  const double r = 0.24, y0 = 1.0, y1 = 1.22;
  write_mesh(dir / "fits.obj", fit_tube(r, y0, y1));
  write_mesh(dir / "cut_small.obj", fit_tube(r, y0, y1, 0.4));  // its pattern 0.603 m around
  const Simulation fits(test::plugins(), parse_scene(fit_scene_text(dir / "fits.obj")));
  CHECK(fits.start_refusal().empty());
  const Simulation small(test::plugins(), parse_scene(fit_scene_text(dir / "cut_small.obj")));
  const std::string why = small.start_refusal();
  CHECK_THAT(why, Catch::Contains("cannot be put on") && Catch::Contains("0.603 m at rest"));
  // The uv_scale named makes the pattern as long around as the body: 0.4 x scale x 2 pi r >= the body's girth.
  const double body = body_girth(small.fit_body(), small.body_model().faces());
  const double scale = std::stod(why.substr(why.find("uv_scale: ") + 10));
  CHECK(scale * 0.4 * 2 * M_PI * r >= body);
  CHECK(scale * 0.4 * 2 * M_PI * r < 1.01 * body);
  // run() refuses it before the first step (a step would be seen by on_step).
  int steps = 0;
  SimulationOptions options;
  options.on_step = [&](const SimulationStep&) { ++steps; };
  CHECK_THROWS_WITH(small.run(small.body_vertices(small.target_shape()), options), Catch::Contains("cannot be put on"));
  CHECK(steps == 0);
  // No fit note before that refusal: it advised a grade, which is refused alike (an outside check).
  {
    const SceneSimulations sims(test::plugins(), parse_scene(fit_scene_text(dir / "cut_small.obj")));
    const BodyModel& model = sims.design().body_model();
    const SceneBody target = scene_body(sims, model.vertices(model.solve(BodyRequest{45.0, 1.75, 1.0})), "bmi 45");
    for (const std::string& note : target.notes) CHECK_THAT(note, !Catch::Contains("gives it its design ease"));
  }
  // Scaled as told, its cloth goes around the body.
  char scaled[80];
  std::snprintf(scaled, sizeof scaled, ", uv_scale: %.6g", scale);
  CHECK(Simulation(test::plugins(), parse_scene(fit_scene_text(dir / "cut_small.obj", "", scaled))).start_refusal().empty());
  // The shape laid flat as its cloth (material_space: rest), modelled inside the body: told to model it around it.
  Mesh inside = fit_tube(0.4 * r, y0, y1);
  write_mesh(dir / "inside.obj", inside);
  CHECK_THAT(Simulation(test::plugins(), parse_scene(fit_scene_text(dir / "inside.obj", "", ", material_space: rest")))
                 .start_refusal(),
             Catch::Contains("cannot be put on") && Catch::Contains("model it around"));
  // A full pattern modelled smaller than the body (its 3D loop 0.6 of the
  // tube's, inside the torso): its cloth goes around, so this is not why it
  // would be refused.
  Mesh crumpled = fit_tube(r, y0, y1);
  crumpled.vertices.col(0) *= 0.6;
  crumpled.vertices.col(2) *= 0.6;
  write_mesh(dir / "crumpled.obj", crumpled);
  const Simulation inside_body(test::plugins(), parse_scene(fit_scene_text(dir / "crumpled.obj")));
  CHECK(inside_body.start_refusal().empty());
  // Should its start cross the body, the hint says it is modelled inside it (a grade would name its own, 1.00).
  CHECK_THAT(start_fit_hint(inside_body), Catch::Contains("modelled inside the body") && !Catch::Contains("grade:"));
}

// The words of a blocked morph, on what each cause measures: a cloth shorter
// around than the body, a stiff material, a short time step, long faces.
TEST_CASE("a blocked morph names its cause: too small, a stiff material, a short step, few Newton iterations or long faces", "[garments][fit]") {
  test::TempDir dir;
  const double r = 0.24, y0 = 1.0, y1 = 1.22;
  write_mesh(dir / "fits.obj", fit_tube(r, y0, y1));
  const Simulation sim(test::plugins(), parse_scene(fit_scene_text(dir / "fits.obj")));
  const Eigen::MatrixX3d& body = sim.fit_body();
  const Eigen::MatrixX3i& faces = sim.body_model().faces();
  const scene_detail::MorphBlocked stalled("", 1, 9, 0.651, 2e-4, true);
  const auto loop_of = [&](const Garment& g) { return garment_material_girth(g.mesh, sim.mean_body()); };
  Garment garment = sim.garment();
  SolverSettings solver;
  // The tube's cloth (1.51 m) is longer around than the mean body: not the girth, and nothing else stands out.
  std::string why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("morph step 1 of 2") && Catch::Contains("65.1 %") &&
                      Catch::Contains("stopped there") && Catch::Contains("girth is not what blocks it") &&
                      Catch::Contains("nothing in the scene"));
  // Aluminium: 1.8e6 N/m against the knit's 34.477 (ArcSim's tables, by hand: 52,200 times).
  garment.materials[0] = MaterialTable::builtin().get("aluminium");
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("5.22e+04 times as stiff"));
  // The knit 500 times as heavy (an outside check's, told nothing stood out),
  // and what the scene's effects leave out (its notes before the run).
  garment = sim.garment();
  const double knit_density = MaterialTable::builtin().get("gray-interlock").density;
  garment.materials[0].density = 500 * knit_density;
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false,
                                        {"the stretching effect's stiffness_scale is 0"});
  CHECK_THAT(why, Catch::Contains("500 times as heavy as ArcSim's knit") &&
                      Catch::Contains("and the stretching effect's stiffness_scale is 0") && !Catch::Contains("nothing in the scene"));
  // A time step a thousandth of the default.
  garment = sim.garment();
  solver.time_step = 1e-4;
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("the time step 0.0001 s"));
  CHECK_THAT(why, !Catch::Contains("times as stiff"));
  // One Newton iteration a morph step (the solver's budget while morphing).
  solver = SolverSettings{};
  solver.max_newton_iterations = 1;
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("each morph step gets 1 Newton iteration (") && !Catch::Contains("nothing in the scene"));
  // The cloth cut to 0.4 of the body: too small, and the remedy named for a garment without sizes.
  solver = SolverSettings{};
  garment.mesh.uv *= 0.4;
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("does not fit this body") && Catch::Contains("grade: auto"));
  why = scene_detail::why_morph_blocked(stalled, 2, garment, loop_of(garment), body, faces, solver, true);
  CHECK_THAT(why, Catch::Contains("size: auto"));
  // Long faces: the tube with 8 columns around (edges about 18 cm).
  write_mesh(dir / "coarse.obj", fit_tube(r, y0, y1, 1.0, 8, 2));
  const Simulation coarse(test::plugins(), parse_scene(fit_scene_text(dir / "coarse.obj")));
  why = scene_detail::why_morph_blocked(stalled, 2, coarse.garment(), loop_of(coarse.garment()), body, faces, solver, false);
  CHECK_THAT(why, Catch::Contains("its faces are long"));
}

// The coarse shirt in aluminium foil on the mean body (it fits the knit):
// the body's last centimetres of growth meet foil that cannot stretch, the
// cloth stops giving way after the first cut, and the run stops at the
// stall, within a few cuts instead of 64 (100 s before), naming the
// material's stiffness, not the girth.
TEST_CASE("a morph into cloth that no longer gives way stops at the stall and says why", "[garments][fit]") {
  test::TempDir dir;
  std::ofstream(dir / "foil.yaml") << "base: " << (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string()
                                   << "\nsolver: {morph_steps: 2, settle_steps: 2}\nmaterials: {knit: aluminium}\n";
  const Simulation sim(test::plugins(), load_scene(dir / "foil.yaml"));
  int steps = 0, last_moves = 0;
  double last_done = -1;
  bool told_in_order = true;
  SimulationOptions options;
  options.on_step = [&](const SimulationStep&) { ++steps; };
  // Each partial move is told (a progress bar shows them): in order, the body's share of the way never falling.
  options.on_partial_move = [&](int step, int total, int moves, double done) {
    told_in_order = told_in_order && step == 1 && total == 4 && moves == last_moves + 1 && done >= last_done && done <= 1;
    last_moves = moves;
    last_done = done;
  };
  const std::string why = test::message_of([&] { sim.run(sim.body_vertices(sim.target_shape()), options); });
  INFO(why);
  CHECK(told_in_order);
  CHECK(last_moves == std::stoi(why.substr(why.find("blocked after ") + 14)));
  CHECK_THAT(why, Catch::Contains("stopped there") && Catch::Contains("girth is not what blocks it") &&
                      Catch::Contains("times as stiff"));
  const int cuts = std::stoi(why.substr(why.find("blocked after ") + 14));
  CHECK(cuts < 64);
  CHECK(cuts >= scene_detail::kStallCuts);
  CHECK(steps == 0);  // stopped in the first morph step
}

// A garment modelled half again as large around as its cloth (a uv_scale
// meant for another file): said before anything is simulated, with the
// uv_scale that makes the cloth the size of the shape, and its fit told by
// the cloth, not by the shape that pulls in as it settles.
TEST_CASE("a garment modelled much larger than its cloth is told so, and its fit measured on the cloth", "[garments][fit]") {
  test::TempDir dir;
  const double r = 0.24, y0 = 1.0, y1 = 1.22;
  write_mesh(dir / "tube.obj", fit_tube(r, y0, y1, 1.0 / 1.5));  // the pattern 2/3 of the shape around
  const SceneSimulations sims(test::plugins(), parse_scene(fit_scene_text(dir / "tube.obj")));
  const Simulation& sim = sims.design();
  CHECK(sim.cloth_loop() == Approx(2 * M_PI * r / 1.5).epsilon(1e-6));  // the pattern's loop, by hand
  const std::string& note = sim.shape_note();
  CHECK_THAT(note, Catch::Contains("modelled 5") && Catch::Contains("longer around than its cloth"));
  CHECK(std::stod(note.substr(note.find("uv_scale: ") + 10)) == Approx(1.5).margin(0.05));
  BodyRequest heavy = sim.target_request();
  heavy.bmi = 40;
  const SceneBody body = scene_body(sims, heavy, "bmi 40");
  REQUIRE_FALSE(body.notes.empty());
  CHECK(body.notes.front() == note);
  // The cloth (1.005 m) against this body's girth, not the shape (1.51 m).
  const double girth = body_girth(body.vertices, sim.body_model().faces());
  const double cloth_ease = 2 * M_PI * r / 1.5 / girth - 1;
  bool told = false;
  for (const std::string& n : body.notes) {
    char ease[40];
    std::snprintf(ease, sizeof ease, "%+.1f %% ease here", 100 * cloth_ease);
    told = told || n.find(ease) != std::string::npos;
  }
  CHECK(told);
  // A tube whose shape is its cloth: no such note.
  write_mesh(dir / "plain.obj", fit_tube(r, y0, y1));
  CHECK(Simulation(test::plugins(), parse_scene(fit_scene_text(dir / "plain.obj"))).shape_note().empty());
}

TEST_CASE("a cloth many times as long around as its shape (UVs in centimetres) is refused before any work", "[garments][fit]") {
  // An outside check's vest with UVs in centimetres ran 330 s before its
  // morph failed ("10260.6 % longer around"); in decimetres 36 s.
  test::TempDir dir;
  const double r = 0.24, y0 = 1.0, y1 = 1.22;
  for (const double unit : {100.0, 10.0}) {
    write_mesh(dir / "tube.obj", fit_tube(r, y0, y1, unit));
    const Simulation sim(test::plugins(), parse_scene(fit_scene_text(dir / "tube.obj")));
    const std::string why = sim.start_refusal();
    INFO(why);
    CHECK_THAT(why, Catch::Contains("times as long around as the garment as modelled") && Catch::Contains("another unit"));
    CHECK(std::stod(why.substr(why.find("uv_scale: ") + 10)) == Approx(1.0 / unit).epsilon(1e-9));  // the unit's power of ten
    int steps = 0;
    SimulationOptions options;
    options.on_step = [&](const SimulationStep&) { ++steps; };
    CHECK_THROWS_WITH(sim.run(sim.body_vertices(sim.target_shape()), options), Catch::Contains("another unit"));
    CHECK(steps == 0);
  }
  // Cloth half again or twice as long as the shape (gathers, a loose cut) is no other unit: simulated.
  for (const double loose : {1.5, 2.5}) {
    write_mesh(dir / "loose.obj", fit_tube(r, y0, y1, loose));
    CHECK(Simulation(test::plugins(), parse_scene(fit_scene_text(dir / "loose.obj"))).start_refusal().empty());
  }
}

TEST_CASE("a cloth a grade below the design size cuts too small is told the grade that puts it on", "[garments][fit]") {
  // An outside check: `grade: 0.5` on a garment that drapes at grade 1 was
  // told its pattern was cut smaller than the body and that a grade would
  // not change that.
  test::TempDir dir;
  write_mesh(dir / "fits.obj", fit_tube(0.24, 1.0, 1.22));
  const Simulation fits(test::plugins(), parse_scene(fit_scene_text(dir / "fits.obj")));
  const double girth = body_girth(fits.fit_body(), fits.body_model().faces());
  scene_detail::PatternSource pattern;
  pattern.grade = 0.5;
  const double loop = 0.6 * girth;  // what grade 0.5 left of a cloth 1.2 times the body around
  const std::string why = scene_detail::cloth_too_short(loop, fits.fit_body(), fits.body_model().faces(), pattern);
  INFO(why);
  REQUIRE_THAT(why, Catch::Contains("cannot be put on") && Catch::Contains("garment: {grade: 0.5} cuts its cloth that small"));
  CHECK_THAT(why, !Catch::Contains("a grade does not change that"));
  const double grade = std::stod(why.substr(why.find("grade ", why.find("that small")) + 6));
  // At that grade the cloth is put on (within the start stretch allowed), a hundredth below it is not.
  const auto loop_at = [&](double g) { return loop * g / pattern.grade; };
  scene_detail::PatternSource design;
  CHECK(scene_detail::cloth_too_short(loop_at(grade), fits.fit_body(), fits.body_model().faces(), design).empty());
  CHECK_FALSE(scene_detail::cloth_too_short(loop_at(grade - 0.01), fits.fit_body(), fits.body_model().faces(), design).empty());
}

TEST_CASE("a barrier set far below its defaults is among the causes a blocked morph names", "[garments][fit]") {
  // An outside check's distance 1e-5 m and stiffness 1e-3 Pa (both in range) blocked the morph, which said
  // "nothing in the scene's material, time step or mesh stands out".
  const auto notes_of = [](const std::string& barrier) {
    std::string all;
    for (const std::string& note :
         Simulation(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                 "effects: {gravity: {}, stretching: {}, barrier: " + barrier + "}\n"))
             .effect_notes())
      all += note + "\n";
    return all;
  };
  const std::string low = notes_of("{distance: 1.0e-5, stiffness: 1.0e-3}");
  CHECK_THAT(low, Catch::Contains("the barrier's distance is 1e-05, under a tenth of its default 0.001") &&
                      Catch::Contains("the barrier's stiffness is 0.001, under a tenth of its default 1000"));
  CHECK_THAT(notes_of("{}"), !Catch::Contains("the barrier's"));
  CHECK_THAT(notes_of("{distance: 5.0e-4}"), !Catch::Contains("the barrier's"));  // half the default: a choice, not a cause
}

TEST_CASE("a material's thickness set in a scene is noted as read by no effect", "[garments][fit]") {
  // An outside check's shirt ten times as thick draped bit for bit as the default, without a word.
  const auto notes_of = [](const std::string& materials) {
    std::string all;
    for (const std::string& note :
         Simulation(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse}}\n"
                                                 "effects: {gravity: {}, stretching: {}, barrier: {}}\n" + materials))
             .effect_notes())
      all += note + "\n";
    return all;
  };
  CHECK_THAT(notes_of("materials: {knit: {base: gray-interlock, thickness: 5.0e-3}}\n"),
             Catch::Contains("knit's thickness is kept with the material, but no effect reads it"));
  CHECK_THAT(notes_of("materials: {knit: {base: gray-interlock, multipliers: {thickness: 2}}}\n"),
             Catch::Contains("knit's thickness is kept"));
  CHECK_THAT(notes_of("materials: {knit: {base: gray-interlock, multipliers: {stretch: 2}}}\n"),
             !Catch::Contains("thickness"));
  CHECK_THAT(notes_of(""), !Catch::Contains("thickness"));
}
