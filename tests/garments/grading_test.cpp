// Grading a garment (garment_grading.hpp, `garment: {grade: g}`): every girth
// and length scaled by g about the centre of its top, its material space with
// it; and the fit note that names the grade a body needs.
#include <drape/errors.hpp>
#include <drape/bodies/fit_body.hpp>
#include <drape/garment_grading.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/registry.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/training/model.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "../../framework/src/scene/separated_start.hpp"
#include "test_support.hpp"

using namespace drape;
using test::message_of;

namespace {

const char* kCoarse = "garment: {template: tshirt, params: {resolution: coarse}}\n"
                      "effects: {gravity: {}, stretching: {}}\n";

}  // namespace

TEST_CASE("grading scales girths by g, lengths by 1 + 0.3 (g - 1), about the top", "[garments][grade]") {
  const Simulation plain(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  Garment g = plain.garment();
  const Garment before = g;
  grade_garment(g, 1.25);
  const double l = 1 + 0.3 * 0.25;
  CHECK(grade_length(1.25) == l);
  CHECK(g.fit_grade == 1.25);  // a scene dresses it on the body of 1.25 times the mean girth
  // The top (neckline height) stays; the hem drops by 7.5 % of the length.
  const auto& x0 = before.mesh.vertices;
  const auto& x1 = g.mesh.vertices;
  CHECK(x1.col(1).maxCoeff() == Approx(x0.col(1).maxCoeff()).margin(1e-12));
  const double length0 = x0.col(1).maxCoeff() - x0.col(1).minCoeff();
  CHECK(x1.col(1).maxCoeff() - x1.col(1).minCoeff() == Approx(l * length0).epsilon(1e-12));
  CHECK(x1.col(0).maxCoeff() - x1.col(0).minCoeff() == Approx(1.25 * (x0.col(0).maxCoeff() - x0.col(0).minCoeff())).epsilon(1e-12));
  // Any horizontal loop through the graded shirt is 1.25 times the loop at the matching height.
  const double top = x0.col(1).maxCoeff(), y = top - 0.4 * length0;
  const Eigen::Vector2d centre(x0.col(0).mean(), x0.col(2).mean());
  const geometry::Girth loop0 = geometry::horizontal_girth(x0, before.mesh.faces, y, centre);
  const geometry::Girth loop1 = geometry::horizontal_girth(x1, g.mesh.faces, top - l * (top - y), centre);
  REQUIRE(loop0.found);
  REQUIRE(loop1.found);
  CHECK(loop1.length == Approx(1.25 * loop0.length).epsilon(1e-6));
  // The pattern: the shirt's panels rise along v, so across (u) by 1.25 and
  // along (v) by between the length's 1.075 and 1.25 (by the slope its
  // heights fit over the chart: the shoulders and sleeves rise slower).
  const Eigen::Vector2d span0 = before.mesh.uv.colwise().maxCoeff() - before.mesh.uv.colwise().minCoeff();
  const Eigen::Vector2d span1 = g.mesh.uv.colwise().maxCoeff() - g.mesh.uv.colwise().minCoeff();
  CHECK(span1.x() / span0.x() == Approx(1.25).epsilon(0.01));
  CHECK(span1.y() / span0.y() > l - 1e-9);
  CHECK(span1.y() / span0.y() < 1.2);

  Garment again = before;
  CHECK_THROWS_AS(grade_garment(again, 2.5), ConfigError);
  grade_garment(again, 1.0);
  CHECK(again.mesh.vertices == before.mesh.vertices);
  CHECK(again.mesh.uv == before.mesh.uv);
  CHECK(again.fit_grade == 1.0);
}

TEST_CASE("grading a pattern chart by chart: across its rise by g, along it by the slope's mix", "[garments][grade]") {
  // A vertical tube (radius 0.2, 0.5 m high) whose one chart is its unrolled
  // pattern, and beside it a flat horizontal square of its own chart: the
  // tube's pattern grows 1.5 around and 1.15 up, the square 1.5 both ways.
  Garment g;
  const int around = 24, rows = 6;
  Mesh& m = g.mesh;
  m.vertices.resize(around * rows + 4, 3);
  m.uv.resize((around + 1) * rows + 4, 2);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * i / around;
      m.vertices.row(j * around + i) << 0.2 * std::cos(a), 1.0 + 0.1 * j, 0.2 * std::sin(a);
    }
    for (int i = 0; i <= around; ++i) m.uv.row(j * (around + 1) + i) << 0.2 * 2 * M_PI * i / around, 0.1 * j;
  }
  std::vector<Eigen::Vector3i> faces, uv_faces;
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      const int ua = j * (around + 1) + i, ub = ua + 1, uc = ua + around + 1, ud = ub + around + 1;
      faces.emplace_back(a, b, d), uv_faces.emplace_back(ua, ub, ud);
      faces.emplace_back(a, d, c), uv_faces.emplace_back(ua, ud, uc);
    }
  const int q = around * rows, uq = (around + 1) * rows;  // the square, at the tube's top, inside it
  m.vertices.bottomRows(4) << -0.1, 1.5, -0.1, 0.1, 1.5, -0.1, 0.1, 1.5, 0.1, -0.1, 1.5, 0.1;
  m.uv.bottomRows(4) << 2.0, 0.0, 2.2, 0.0, 2.2, 0.2, 2.0, 0.2;
  faces.emplace_back(q, q + 2, q + 1), uv_faces.emplace_back(uq, uq + 2, uq + 1);
  faces.emplace_back(q, q + 3, q + 2), uv_faces.emplace_back(uq, uq + 3, uq + 2);
  m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  m.uv_faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    m.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose(), m.uv_faces.row(static_cast<Eigen::Index>(f)) = uv_faces[f].transpose();
  const Mesh before = m;
  grade_garment(g, 1.5);
  const double l = 1.15;
  // The tube's chart: the rows' lengths (around) by 1.5, the columns' (up) by 1.15.
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < around; ++i) {
      const int u = j * (around + 1) + i;
      CHECK((m.uv.row(u + 1) - m.uv.row(u)).norm() == Approx(1.5 * (before.uv.row(u + 1) - before.uv.row(u)).norm()).epsilon(1e-9));
      if (j + 1 < rows)
        CHECK((m.uv.row(u + around + 1) - m.uv.row(u)).norm() == Approx(l * 0.1).epsilon(1e-9));
    }
  // The square lies flat: all of it goes around the body, 1.5 both ways.
  for (int k = 1; k < 4; ++k)
    CHECK((m.uv.row(uq + k) - m.uv.row(uq)).norm() == Approx(1.5 * (before.uv.row(uq + k) - before.uv.row(uq)).norm()).epsilon(1e-9));
  // In 3D: 1.5 around, 1.15 down from the top.
  CHECK(m.vertices(0, 0) == Approx(0.3));
  CHECK(m.vertices(0, 1) == Approx(1.5 - l * 0.5));
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
  // Dressed on its fit body (1.2 times the mean girth), the graded shirt is about 1.2 times as wide around
  // (dressing moves it by millimetres), and every run starts from that body.
  CHECK(loop(big) / loop(plain) == Approx(1.2).epsilon(0.02));
  CHECK(big.garment().fit_grade == 1.2);
  CHECK(body_girth(big.fit_body(), big.body_model().faces()) / body_girth(big.mean_body(), big.body_model().faces()) ==
        Approx(1.2).epsilon(2e-3));
  CHECK(plain.fit_body() == plain.mean_body());
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
                               parse_scene("garment: {template: tshirt, params: {resolution: coarse}, grade: 0.5}\n"
                                           "effects: {gravity: {}, stretching: {}, barrier: {}}\n",
                                           "tight.yaml"));
  const Simulation& d = tight.design();
  // The hint measures the garment as graded (its loop 0.6 times the template's), not as dressing pushed it out.
  // (Since the sizes' fit bodies, a graded garment is put on the body of its
  // girth; grade 0.5 is below the thinnest body, BMI 10 at 0.56 of the mean
  // girth, so it is still smaller than the body it is put on.)
  CHECK(d.placed_loop() == Approx(0.5 * d.design_loop()).epsilon(0.02));
  const std::string hint = start_fit_hint(d);
  CHECK_THAT(hint, Catch::Contains("smaller around than the body it is put on") && Catch::Contains("gives it its design ease"));
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

TEST_CASE("place_graded_garment carries a garment with its body's growth, outside the fit body", "[garments][grade]") {
  // The regular coarse shirt, dressed on the mean body, carried to the body of
  // 1.3 times its girth: every vertex keeps its place on the body and its
  // offset grows with the grade, so the shirt stays around the larger body.
  const Simulation plain(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  const BodyModel& model = plain.body_model();
  const FitBody fit = fit_body(model, 1.3);
  REQUIRE_FALSE(fit.clamped);
  Garment garment = plain.garment();
  const Eigen::MatrixX3d ungraded = garment.mesh.vertices;
  place_graded_garment(garment, ungraded, plain.mean_body(), fit.vertices, model.faces(), 1.3);
  const Eigen::VectorXd before = geometry::BodySurface(plain.mean_body(), model.faces()).signed_distances(ungraded);
  const Eigen::VectorXd placed = geometry::BodySurface(fit.vertices, model.faces()).signed_distances(garment.mesh.vertices);
  // Further from the fit body on average than from the mean body (1.11
  // times: the offsets grow by 1.3, and the smoothing pulls some vertices of
  // the sleeves, bound to arm and torso, in: 52 of 991 inside), and wholly
  // outside once dressed on it, as Simulation does.
  INFO("mean distance " << before.mean() << " m on the mean body, " << placed.mean() << " m on the fit body; inside "
                        << (placed.array() < 0).count());
  CHECK(placed.mean() / before.mean() > 1.05);
  CHECK(placed.mean() / before.mean() < 1.5);
  CHECK((placed.array() < 0).count() <= placed.size() / 10);
  dress(garment, Mesh{fit.vertices, model.faces(), {}, {}});
  const Eigen::VectorXd after = geometry::BodySurface(fit.vertices, model.faces()).signed_distances(garment.mesh.vertices);
  CHECK((after.array() < 0).count() == 0);
  // A start the barrier accepts: clear of the fit body, or of it shrunk by a
  // few centimetres (the coarse shirt's armholes cross the arms as designed:
  // 14 body edges through its faces on the mean body, 17 here).
  double shrink = -1;
  CHECK_NOTHROW(scene_detail::separated_start_body(garment.mesh.vertices, fit.vertices, model.faces(), garment.mesh.faces, &shrink));
  CHECK(shrink <= 0.03);
  // Around it: its girth at the body's widest grows with the body's.
  CHECK(garment_girth(garment.mesh.vertices, garment.mesh.faces, fit.vertices) /
            garment_girth(ungraded, garment.mesh.faces, plain.mean_body()) ==
        Approx(1.3).epsilon(0.05));
  // Vertices and bodies that do not match are refused.
  Garment other = plain.garment();
  CHECK_THROWS(place_graded_garment(other, ungraded.topRows(10), plain.mean_body(), fit.vertices, model.faces(), 1.3));
}

TEST_CASE("grading an outfit keeps the trousers' lengths and the floor and passes no piece through another", "[garments][grade]") {
  // MakeHuman's suit (a shirt and jeans) at grade 1.35 had its jeans' hems
  // graded 16 cm down about the shirt's top, through the feet and the floor,
  // and its start was refused (an outside check); graded about their own top
  // instead, the shirt's hem went through the jeans' waist.
  const Simulation plain(test::plugins(), parse_scene(kCoarse, "plain.yaml"));
  const Garment shirt = plain.garment();
  const Eigen::Index n = shirt.mesh.vertices.rows();
  // The outfit: the shirt, and a second piece under it hanging from its hem
  // height down to 2 cm above the floor (a copy of the shirt taken in to
  // 0.8 of its girth and stretched down: a skirt as far as grading sees it).
  const double floor = 0.0, crotch = 0.8;
  const double shirt_top = shirt.mesh.vertices.col(1).maxCoeff(), shirt_low = shirt.mesh.vertices.col(1).minCoeff();
  Garment outfit = shirt;
  outfit.mesh.vertices.resize(2 * n, 3);
  outfit.mesh.vertices.topRows(n) = shirt.mesh.vertices;
  const double cx = shirt.mesh.vertices.col(0).mean(), cz = shirt.mesh.vertices.col(2).mean();
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::RowVector3d p = shirt.mesh.vertices.row(v);
    const double t = (p.y() - shirt_low) / (shirt_top - shirt_low);  // 0 at the hem, 1 at the top
    outfit.mesh.vertices.row(n + v) << cx + 0.8 * (p.x() - cx), 0.02 + t * (shirt_low + 0.1 - 0.02), cz + 0.8 * (p.z() - cz);
  }
  outfit.mesh.faces.resize(2 * shirt.mesh.faces.rows(), 3);
  outfit.mesh.faces << shirt.mesh.faces, (shirt.mesh.faces.array() + static_cast<int>(n)).matrix();
  outfit.mesh.uv.resize(2 * shirt.mesh.uv.rows(), 2);
  outfit.mesh.uv << shirt.mesh.uv, shirt.mesh.uv;
  outfit.mesh.uv_faces.resize(2 * shirt.mesh.uv_faces.rows(), 3);
  outfit.mesh.uv_faces << shirt.mesh.uv_faces, (shirt.mesh.uv_faces.array() + static_cast<int>(shirt.mesh.uv.rows())).matrix();
  const Garment before = outfit;
  grade_garment(outfit, 1.35, crotch, floor);
  const auto& x0 = before.mesh.vertices;
  const auto& x1 = outfit.mesh.vertices;
  // The floor is kept: the lower piece's hem stays above it.
  CHECK(x1.bottomRows(n).col(1).minCoeff() >= floor);
  CHECK(x1.bottomRows(n).col(1).minCoeff() <= x0.bottomRows(n).col(1).minCoeff());
  // The shirt, above the crotch, is graded as it is alone.
  Garment alone = shirt;
  grade_garment(alone, 1.35);
  CHECK((x1.topRows(n) - alone.mesh.vertices).cwiseAbs().maxCoeff() < 1e-12);
  // One map of heights for every piece: what lay above another still does.
  for (Eigen::Index v = 0; v < 2 * n; v += 37)
    for (Eigen::Index w = 0; w < 2 * n; w += 41)
      if (x0(v, 1) < x0(w, 1)) CHECK(x1(v, 1) <= x1(w, 1));
  // The lower piece's cloth keeps its lengths along its rise (v) and grows around (u) by 1.35; the shirt's grows along v.
  const auto span = [](const Eigen::MatrixX2d& uv) { return Eigen::Vector2d(uv.colwise().maxCoeff() - uv.colwise().minCoeff()); };
  const Eigen::Index m = shirt.mesh.uv.rows();
  const Eigen::Vector2d lower0 = span(before.mesh.uv.bottomRows(m)), lower1 = span(outfit.mesh.uv.bottomRows(m));
  const Eigen::Vector2d upper0 = span(before.mesh.uv.topRows(m)), upper1 = span(outfit.mesh.uv.topRows(m));
  CHECK(upper1.y() > 1.05 * upper0.y());
  CHECK(lower1.y() < upper1.y() / upper0.y() * lower0.y() - 1e-6);
  CHECK(lower1.x() == Approx(upper1.x() / upper0.x() * lower0.x()).epsilon(1e-3));  // (the charts' slopes mix u a little)
}
