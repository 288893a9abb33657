// garment: {grade: auto} (scene/auto_grade.hpp): each body wears the grade
// that gives it the garment's design ease, refused before any simulation when
// that grade is outside 0.5-2.
#include <drape/errors.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/registry.hpp>
#include <drape/scene/auto_grade.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/scene_body.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"

using namespace drape;
using test::message_of;

namespace {

const char* kAuto = "garment: {template: tshirt, params: {resolution: coarse}, grade: auto}\n"
                    "effects: {gravity: {}, stretching: {}}\n";

// The largest horizontal tape measure around a mesh between 58 and 72 % of
// its height, written here from the tailor's rule's words (not garment_size's
// code) with the girth routine both share.
double chest_or_belly(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces) {
  const double y0 = body.col(1).minCoeff(), h = body.col(1).maxCoeff() - y0;
  double best = 0;
  for (int i = 0; i <= 70; ++i) {
    const geometry::Girth g = geometry::horizontal_girth(body, faces, y0 + (0.58 + 0.002 * i) * h, {0.0, 0.0});
    if (g.found) best = std::max(best, g.length);
  }
  return best;
}

}  // namespace

TEST_CASE("grade auto parses and is written back as auto", "[garments][grade]") {
  const Scene s = parse_scene(kAuto, "auto.yaml");
  CHECK(s.garment_grade_auto);
  CHECK(s.garment_grade == 1.0);
  CHECK(parse_scene(s.yaml(), "again.yaml").garment_grade_auto);
  CHECK_THAT(message_of([] { parse_scene("garment: {grade: big}\n", "bad.yaml"); }),
             Catch::Contains("bad.yaml:1") && Catch::Contains("or auto"));
  // One Simulation is one garment: grade: auto goes through SceneSimulations.
  CHECK_THAT(message_of([&] { Simulation(test::plugins(), s); }), Catch::Contains("chosen per body"));
  CHECK_THAT(message_of([] {
               SceneSimulations(test::plugins(), parse_scene("garment: {template: tshirt, params: {resolution: coarse, "
                                                             "size: auto}, grade: auto}\n",
                                                             "both.yaml"));
             }),
             Catch::Contains("choose the same thing twice"));
}

TEST_CASE("grade auto gives each body the design ease and refuses a body beyond grade 2", "[garments][grade]") {
  const SceneSimulations sims(test::plugins(), parse_scene(kAuto, "auto.yaml"));
  REQUIRE(sims.auto_grade());
  const Simulation& design = sims.design();
  const Eigen::MatrixX3i& faces = design.body_model().faces();
  const double ease0 = sims.grades()->design_ease();
  CHECK(ease0 > 0.05);  // a T-shirt has ease on the body it was made for
  CHECK(ease0 < 0.30);

  // The mean body wears the garment as designed.
  GradeChoice mean_choice;
  const Simulation& on_mean = sims.for_body(design.mean_body(), "mean", nullptr, &mean_choice);
  CHECK(&on_mean == &design);
  CHECK(mean_choice.exact == Approx(1.0).margin(1e-9));

  // A heavy body: the graded garment, measured as worn, has the design ease
  // within the rounding of the grade (half a step of 0.05 on a grade near 1.5).
  BodyRequest heavy = design.body_model().mean_request();
  heavy.bmi = 45;
  const Eigen::MatrixX3d body = design.body_vertices(design.shape_for(heavy));
  GradeChoice choice;
  const Simulation& graded = sims.for_body(body, "heavy", nullptr, &choice);
  CHECK(choice.body_girth == Approx(chest_or_belly(body, faces)).epsilon(0.01));
  CHECK(choice.grade > 1.2);
  CHECK(std::abs(choice.grade - choice.exact) <= kAutoGradeStep / 2 + 1e-12);
  CHECK(graded.scene().garment_grade == Approx(choice.grade));
  const double worn_ease = graded.placed_loop() / chest_or_belly(body, faces) - 1.0;
  CHECK(worn_ease == Approx(ease0).margin(0.03));
  // Built once per grade: a second body of that grade gets the same garment.
  CHECK(&sims.for_body(body, "heavy again") == &graded);

  // A body twice as wide as the mean one needs more than grade 2: refused,
  // naming its girth and the grade, before anything is simulated.
  Eigen::MatrixX3d wide = design.mean_body();
  wide.col(0) *= 2.3;
  wide.col(2) *= 2.3;
  const std::string message = message_of([&] { sims.for_body(wide, "wide body"); });
  CHECK_THAT(message, Catch::Contains("wide body") && Catch::Contains("cannot fit this body") &&
                          Catch::Contains("needs grade 2.") && Catch::Contains("outside the 0.5-2"));
  // scene_body tells the grade it chose.
  const SceneBody sb = scene_body(sims, body, "heavy.obj");
  REQUIRE(sb.grade);
  CHECK(sb.grade->grade == choice.grade);
  CHECK(sb.simulation == &graded);
}

TEST_CASE("grade auto's steps are a size chart that chooses as it does", "[garments][grade]") {
  const SceneSimulations sims(test::plugins(), parse_scene(kAuto, "auto.yaml"));
  const SizeTable& t = sims.grades()->table();
  // From the first step the parametric body dresses (g0.60: below, the thinnest grade auto's test below) to g2.00.
  REQUIRE(t.girth.size() == 29);
  CHECK(t.girth.front().first == "g0.60");
  CHECK(t.girth.back().first == "g2.00");
  CHECK(t.design == "g1.00");
  CHECK(t.grade("g1.35") == Approx(1.35).epsilon(1e-12));
  // Text round trip: what a dataset and a model keep.
  const SizeTable back = SizeTable::parse(t.to_text(), "chart");
  CHECK(back.grade("g0.75") == Approx(0.75).epsilon(1e-12));
  // Over the body space's girths the chart's choice is the grade chosen.
  const Simulation& design = sims.design();
  for (double bmi : {12.0, 20.0, 30.0, 40.0, 50.0, 64.0}) {
    BodyRequest r = design.body_model().mean_request();
    r.bmi = bmi;
    const Eigen::MatrixX3d body = design.body_vertices(design.shape_for(r));
    const GradeChoice c = sims.grades()->choose(body, "body");
    INFO("BMI " << bmi << ": " << c.summary());
    CHECK(c.grade == Approx(t.grade(t.choose(c.body_girth).size)));
    CHECK(std::abs(c.grade - c.exact) <= kAutoGradeStep / 2 + 1e-9);
  }
}

TEST_CASE("grade auto's smallest step is one the body model dresses: the thinnest body starts", "[garments][grade]") {
  // Before, the chart began at g0.50 whatever the body model, and a BMI 10
  // body (chest 0.553 m) was given g0.55: a garment tighter than the thinnest
  // body the model makes at its mean height, which every graded garment is
  // dressed on and morphs from, so every such drape was refused at its start
  // as a crossing.
  const char* text = "garment: {template: tshirt, params: {resolution: coarse}, grade: auto}\n"
                     "effects: [gravity, stretching, bending, barrier]\n"
                     "solver: {morph_steps: 1, settle_steps: 1, max_newton_iterations: 5}\n";
  const SceneSimulations sims(test::plugins(), parse_scene(text, "thin.yaml"));
  const Simulation& design = sims.design();
  const BodyModel& model = design.body_model();
  const Eigen::MatrixX3i& faces = model.faces();
  // The thinnest body at the mean height and sex, measured by this file's tape.
  BodyRequest thinnest_request = model.mean_request();
  thinnest_request.bmi = model.bmi_range().first;
  const double thinnest = chest_or_belly(design.body_vertices(model.solve(thinnest_request)), faces) /
                          chest_or_belly(design.mean_body(), faces);
  INFO("the thinnest body's girth over the mean body's: " << thinnest);
  REQUIRE(thinnest > 0.55);  // the case this is about: thinner grades exist in 0.5-2 that no body wears
  const SizeTable& t = sims.grades()->table();
  const double smallest = t.grade(t.girth.front().first);
  CHECK(smallest >= thinnest - 0.005);
  CHECK(smallest - kAutoGradeStep < thinnest);

  // A short thin woman needs less than that step: she wears it, and is told why.
  BodyRequest thin = model.mean_request();
  thin.bmi = 10, thin.height = 1.5, thin.sex = 0;
  const Eigen::MatrixX3d body = design.body_vertices(design.shape_for(thin));
  GradeChoice choice;
  const Simulation& graded = sims.for_body(body, "thin", nullptr, &choice);
  CHECK(choice.exact < smallest - kAutoGradeStep / 2);
  CHECK(choice.grade == Approx(smallest));
  CHECK(choice.at_smallest);
  CHECK_THAT(choice.summary(), Catch::Contains("the smallest grade the body model dresses"));
  // It starts: dressed on its fit body with no crossing, and a step is taken.
  int steps = 0;
  SimulationOptions options;
  options.on_step = [&](const SimulationStep&) { ++steps; };
  const SimulationResult result = graded.run(body, options);
  CHECK(steps >= 1);
  REQUIRE(result.crossings);
  CHECK(result.crossings->total() == 0);
  // A body that needs a step the chart has is not told so.
  BodyRequest mean = model.mean_request();
  mean.bmi = 18;
  GradeChoice usual;
  sims.for_body(design.body_vertices(design.shape_for(mean)), "usual", nullptr, &usual);
  CHECK_FALSE(usual.at_smallest);
  CHECK_THAT(usual.summary(), !Catch::Contains("smallest"));
}
