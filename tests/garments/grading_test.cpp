// Grading a garment (garment_grading.hpp, `garment: {grade: g}`): every girth
// and length scaled by g about the centre of its top, its material space with
// it; and the fit note that names the grade a body needs.
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/registry.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/training/model.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"

using namespace drape;
using test::message_of;

namespace {

const char* kCoarse = "garment: {template: tshirt, params: {resolution: coarse}}\n"
                      "effects: {gravity: {}, stretching: {}}\n";

// The rest garment's edge lengths in the material space.
Eigen::VectorXd uv_edge_lengths(const Mesh& m) {
  Eigen::VectorXd out(3 * m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      out(3 * f + k) = (m.uv.row(m.uv_faces(f, (k + 1) % 3)) - m.uv.row(m.uv_faces(f, k))).norm();
  return out;
}

}  // namespace

TEST_CASE("grading scales girths, lengths and the pattern by g about the top", "[garments][grade]") {
  const Simulation plain(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  Garment g = plain.garment();
  const Garment before = g;
  grade_garment(g, 1.25);
  // The pattern's every edge is 1.25 times longer: the cloth's rest lengths grew.
  CHECK(uv_edge_lengths(g.mesh).isApprox(1.25 * uv_edge_lengths(before.mesh), 1e-12));
  // The top (neckline height) stays; the hem drops by a quarter of the length.
  const auto& x0 = before.mesh.vertices;
  const auto& x1 = g.mesh.vertices;
  CHECK(x1.col(1).maxCoeff() == Approx(x0.col(1).maxCoeff()).margin(1e-12));
  const double length0 = x0.col(1).maxCoeff() - x0.col(1).minCoeff();
  CHECK(x1.col(1).maxCoeff() - x1.col(1).minCoeff() == Approx(1.25 * length0).epsilon(1e-12));
  // Any horizontal loop through the graded shirt is 1.25 times the loop at the matching height.
  const double top = x0.col(1).maxCoeff(), y = top - 0.4 * length0;
  const Eigen::Vector2d centre(x0.col(0).mean(), x0.col(2).mean());
  const geometry::Girth loop0 = geometry::horizontal_girth(x0, before.mesh.faces, y, centre);
  const geometry::Girth loop1 = geometry::horizontal_girth(x1, g.mesh.faces, top - 1.25 * (top - y), centre);
  REQUIRE(loop0.found);
  REQUIRE(loop1.found);
  CHECK(loop1.length == Approx(1.25 * loop0.length).epsilon(1e-6));

  Garment again = before;
  CHECK_THROWS_AS(grade_garment(again, 2.5), ConfigError);
  grade_garment(again, 1.0);
  CHECK(again.mesh.vertices == before.mesh.vertices);
}

TEST_CASE("a scene's grade is parsed, checked, recorded and applied before dressing", "[garments][grade]") {
  const Scene graded = parse_scene("garment: {template: tshirt, params: {resolution: coarse}, grade: 1.2}\n"
                                   "effects: {gravity: {}, stretching: {}}\n",
                                   "graded.yaml");
  CHECK(graded.garment_grade == 1.2);
  CHECK(parse_scene(graded.yaml(), "again.yaml").garment_grade == 1.2);  // datasets record it
  CHECK(parse_scene(kCoarse, "plain.yaml").yaml().find("grade") == std::string::npos);  // old scene texts unchanged
  CHECK_THAT(message_of([] { parse_scene("garment:\n  grade: 3\n", "s.yaml"); }),
             Catch::Contains("s.yaml:2") && Catch::Contains("outside 0.5 to 2"));
  CHECK_THAT(message_of([] { parse_scene("garment: {grade: big}\n", "s.yaml"); }), Catch::Contains("must be a number"));
  CHECK_THAT(message_of([] { parse_scene("garment: {grad: 1.1}\n", "s.yaml"); }), Catch::Contains("grade"));

  const Simulation plain(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  const Simulation big(test::plugins(), graded);
  const auto loop = [](const Simulation& s) {
    return garment_girth(s.garment().mesh.vertices, s.garment().mesh.faces, s.mean_body());
  };
  // Dressed on the mean body, the graded shirt is about 1.2 times as wide around (dressing moves it by millimetres).
  CHECK(loop(big) / loop(plain) == Approx(1.2).epsilon(0.02));
  // A model's template is ungraded: its drapes are refused for training.
  CHECK_THROWS_WITH(assets_spec_for(graded, 16, 4), Catch::Contains("graded"));
}

TEST_CASE("simulate's fit note names the grade that gives a body the design ease", "[garments][grade]") {
  const Scene scene = parse_scene(kCoarse, "plain.yaml");
  const SceneSimulations simulations(test::plugins(), scene);
  BodyRequest heavy = simulations.design().target_request();
  heavy.bmi = 45;
  const SceneBody body = scene_body(simulations, heavy, "bmi 45");
  REQUIRE(body.notes.size() == 1);
  CHECK_THAT(body.notes[0], Catch::Contains("smaller around") && Catch::Contains("garment: {grade: 1."));
  // The grade it names does give that body the mean body's ease, to the note's two decimals.
  const std::string& note = body.notes[0];
  const double grade = std::stod(note.substr(note.find("grade: ") + 7));
  const Simulation& d = simulations.design();
  const double loop = garment_girth(d.garment().mesh.vertices, d.garment().mesh.faces, d.mean_body());
  const double design_ease = garment_ease(loop, d.mean_body(), d.body_model().faces());
  CHECK(garment_ease(grade * loop, body.vertices, d.body_model().faces()) == Approx(design_ease).margin(0.01));
  // A graded scene names the same grade of the template, and says how far it is from it now.
  const SceneSimulations graded(test::plugins(),
                                parse_scene("garment: {template: tshirt, params: {resolution: coarse}, grade: 1.35}\n"
                                            "effects: {gravity: {}, stretching: {}}\n",
                                            "graded.yaml"));
  const SceneBody graded_body = scene_body(graded, heavy, "bmi 45");
  REQUIRE(graded_body.notes.size() == 1);
  const std::string& graded_note = graded_body.notes[0];
  CHECK(std::stod(graded_note.substr(graded_note.find("grade: ") + 7)) == Approx(grade).margin(0.015));
  CHECK_THAT(graded_note, Catch::Contains("+6.2 % on the mean body"));
  // The mean body needs no note.
  CHECK(scene_body(simulations, simulations.design().target_request(), "mean").notes.empty());
}

// A garment smaller around than the mean body it is put on cannot be put on:
// the contact refuses the start before the first step, and the refusal says
// how much smaller, with the loop, the body's girth and the grade that fits.
TEST_CASE("a garment graded smaller than the mean body is refused at the start and told the grade that fits", "[garments][grade]") {
  const SceneSimulations tight(test::plugins(),
                               parse_scene("garment: {template: tshirt, params: {resolution: coarse}, grade: 0.6}\n"
                                           "effects: {gravity: {}, stretching: {}, barrier: {}}\n",
                                           "tight.yaml"));
  const Simulation& d = tight.design();
  // The hint measures the garment as graded (its loop 0.6 times the template's), not as dressing pushed it out.
  CHECK(d.placed_loop() == Approx(0.6 * d.design_loop()).epsilon(0.02));
  const std::string hint = start_fit_hint(d);
  CHECK_THAT(hint, Catch::Contains("smaller around than the mean body") && Catch::Contains("garment: {grade: 1.00}"));
  BodyRequest request = d.target_request();
  request.bmi = 40;
  const SceneBody body = scene_body(tight, request, "bmi 40");
  CHECK_THROWS_WITH(drape_scene_body(body), Catch::Contains("starts crossing the body") && Catch::Contains(hint));
  // The regular shirt fits the mean body: nothing to add.
  const SceneSimulations regular(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  CHECK(start_fit_hint(regular.design()).empty());
}

// The other measure of the tailor's rule: how far down a top reaches. The
// parametric body keeps its proportions with height, so the torso's length
// scales with it, and the grade that gives a shirt its design length is the
// height ratio (worked by hand, not by the code's slicing).
TEST_CASE("simulate's length note names the grade that gives a tall or short body the design length", "[garments][grade]") {
  const SceneSimulations simulations(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  const Simulation& d = simulations.design();
  const double mean_height = d.mean_body().col(1).maxCoeff() - d.mean_body().col(1).minCoeff();
  const auto length_note = [&](double height) {
    BodyRequest r = d.target_request();
    r.height = height;
    for (const std::string& n : scene_body(simulations, r, "body").notes)
      if (n.find("of the way from its neckline") != std::string::npos) return n;
    return std::string();
  };
  const std::string tall = length_note(2.0), short_one = length_note(1.5);
  CHECK_THAT(tall, Catch::Contains("ends higher"));
  CHECK_THAT(short_one, Catch::Contains("ends lower"));
  const auto grade = [](const std::string& note) { return std::stod(note.substr(note.find("grade: ") + 7)); };
  CHECK(grade(tall) == Approx(2.0 / mean_height).margin(0.03));
  CHECK(grade(short_one) == Approx(1.5 / mean_height).margin(0.03));
  CHECK(length_note(mean_height).empty());
}
