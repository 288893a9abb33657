// The body space drape samples (body_space.hpp): BMI uniform and, independently,
// sex, height and the parametric body's six girths; every corner of it a valid
// body on target BMI; requests with proportions a model lacks refused.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/bodies/body_space.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/volume.hpp>
#include <test_support.hpp>

#include <cmath>
#include <memory>

namespace {

using namespace drape;

const BodyModel& parametric() {
  static const std::unique_ptr<BodyModel> model = [] {
    const PluginDescriptor& d = test::plugins().get("parametric");
    return test::plugins().create_body("parametric", Params(d.params, {}, "body parametric"));
  }();
  return *model;
}

double measured_bmi(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) {
  const double h = v.col(1).maxCoeff() - v.col(1).minCoeff();
  return geometry::mesh_volume(v, f) * 985.0 / (h * h);
}

const std::vector<std::string> kGirths = {"chest", "waist", "belly", "hips", "arms", "thighs"};

}  // namespace

TEST_CASE("body space: the parametric body offers its six girths as proportions", "[bodies][space]") {
  std::vector<std::string> names;
  for (const auto& p : parametric().proportions()) {
    names.push_back(p.name);
    CHECK(p.min < 0);
    CHECK(p.max > 0);
  }
  CHECK(names == kGirths);
}

TEST_CASE("body space: draws are uniform and independent in BMI, height, sex and girths", "[bodies][space]") {
  BodySpace space;  // BMI 10-65, height 1.5-2.0, both sexes, full girth spread
  Rng rng(7);
  const int n = 4000;
  double sum_bmi = 0, sum_h = 0, sum_bh = 0, sum_b2 = 0, sum_h2 = 0;
  int female = 0;
  std::map<std::string, double> girth_sum;
  for (int i = 0; i < n; ++i) {
    const BodyRequest r = draw_body(space, parametric(), rng);
    REQUIRE(r.bmi >= 10);
    REQUIRE(r.bmi < 65);
    REQUIRE(r.height >= 1.5);
    REQUIRE(r.height < 2.0);
    REQUIRE((r.sex == 0.0 || r.sex == 1.0));
    REQUIRE(r.proportions.size() == 6);
    for (const auto& [name, v] : r.proportions) {
      REQUIRE(std::abs(v) <= 0.15);
      girth_sum[name] += v;
    }
    female += r.sex == 0.0;
    sum_bmi += r.bmi;
    sum_h += r.height;
    sum_bh += r.bmi * r.height;
    sum_b2 += r.bmi * r.bmi;
    sum_h2 += r.height * r.height;
  }
  // Uniform on [10, 65): mean 37.5, standard error 15.9 / sqrt(4000) = 0.25.
  CHECK(sum_bmi / n == Approx(37.5).margin(1.0));
  CHECK(sum_h / n == Approx(1.75).margin(0.01));
  CHECK(female / double(n) == Approx(0.5).margin(0.03));
  for (const auto& [name, s] : girth_sum) CHECK(s / n == Approx(0.0).margin(0.006));
  const double cov = sum_bh / n - (sum_bmi / n) * (sum_h / n);
  const double r = cov / std::sqrt((sum_b2 / n - std::pow(sum_bmi / n, 2)) * (sum_h2 / n - std::pow(sum_h / n, 2)));
  CHECK(std::abs(r) < 0.05);

  // Spread 0 keeps the mean build; a fixed sex stays fixed; the same seed gives the same bodies.
  space.proportion_spread = 0;
  space.sex_lo = space.sex_hi = 0;
  Rng a(3), b(3);
  const BodyRequest ra = draw_body(space, parametric(), a), rb = draw_body(space, parametric(), b);
  CHECK(ra.proportions.empty());
  CHECK(ra.sex == 0);
  CHECK(ra.bmi == rb.bmi);
}

TEST_CASE("body space: every corner is a valid body on target BMI", "[bodies][space]") {
  for (const double sex : {0.0, 1.0})
    for (const double height : {1.5, 2.0})
      for (const double bmi : {10.0, 65.0})
        for (const double girth : {-0.15, 0.15}) {
          BodyRequest r{bmi, height, sex, {}};
          for (const auto& g : kGirths) r.proportions[g] = girth;
          int halvings = -1;
          const Eigen::VectorXd shape = solve_in_space(parametric(), r, &halvings);
          const Eigen::MatrixX3d v = parametric().vertices(shape);
          const Eigen::MatrixX3i& f = parametric().faces();
          INFO("sex " << sex << ", height " << height << ", BMI " << bmi << ", girths " << girth << ", halvings " << halvings);
          CHECK(measured_bmi(v, f) == Approx(bmi).margin(0.5));
          CHECK(v.col(1).maxCoeff() - v.col(1).minCoeff() == Approx(height).margin(1e-6));
          CHECK(geometry::check_topology(f, static_cast<int>(v.rows())).closed_manifold());
          CHECK(geometry::self_intersections(v, f, 10).empty());
          if (halvings == 0) {
            for (const auto& g : kGirths) CHECK(r.proportions.at(g) == girth);
          } else {
            // The lean-and-light corner: broad girths cannot reach BMI 10 on a short male body.
            CHECK((sex == 1.0 && height == 1.5 && bmi == 10.0 && girth > 0));
            CHECK(std::abs(r.proportions.at("chest")) < std::abs(girth));
          }
        }
}

TEST_CASE("body space: girths that make the body pass through itself are halved until it does not", "[bodies][space]") {
  // Sample 1018 of the 2,000-drape run (seed 1): a man of BMI 10.2 with broad
  // arms, whose upper arms cross his torso in the armpits as drawn.
  BodyRequest r{10.2426, 1.77352, 1.0, {{"arms", 0.110223}, {"belly", 0.0659977}, {"chest", -0.0387222},
                                       {"hips", 0.125589}, {"thighs", 0.0889141}, {"waist", 0.00915949}}};
  const Eigen::MatrixX3i& f = parametric().faces();
  REQUIRE_FALSE(geometry::self_intersections(parametric().vertices(parametric().solve(r)), f, 1).empty());
  int halvings = -1;
  const Eigen::MatrixX3d v = parametric().vertices(solve_in_space(parametric(), r, &halvings));
  CHECK(halvings >= 1);
  CHECK(geometry::self_intersections(v, f, 10).empty());
  CHECK(measured_bmi(v, f) == Approx(10.2426).margin(0.5));
  CHECK(r.proportions.at("arms") < 0.110223);
  // The mixed corners: broad arms and thighs on the leanest and the heaviest bodies, everything else narrow.
  for (const double sex : {0.0, 1.0})
    for (const double height : {1.5, 2.0})
      for (const double bmi : {10.0, 65.0}) {
        BodyRequest mixed{bmi, height, sex, {}};
        for (const auto& g : kGirths) mixed.proportions[g] = (g == "arms" || g == "thighs") ? 0.15 : -0.15;
        const Eigen::MatrixX3d w = parametric().vertices(solve_in_space(parametric(), mixed));
        INFO("sex " << sex << ", height " << height << ", BMI " << bmi);
        CHECK(geometry::self_intersections(w, f, 10).empty());
        CHECK(measured_bmi(w, f) == Approx(bmi).margin(0.5));
      }
}

TEST_CASE("body space: proportions a model lacks or out of range are refused by name", "[bodies][space]") {
  BodyRequest r;
  r.proportions["neck"] = 0.1;
  CHECK_THAT(test::message_of([&] { parametric().solve(r); }),
             Catch::Contains("no proportion 'neck'") && Catch::Contains("chest, waist, belly, hips, arms, thighs"));
  r.proportions = {{"hips", 0.4}};
  CHECK_THAT(test::message_of([&] { parametric().solve(r); }), Catch::Contains("proportion 'hips' = 0.4 is outside [-0.15, 0.15]"));

  // A model offering none (as SMPL and MakeHuman) refuses any.
  struct Plain final : BodyModel {
    int num_vertices() const override { return 0; }
    const Eigen::MatrixX3i& faces() const override { return f; }
    std::vector<std::string> shape_names() const override { return {}; }
    Eigen::VectorXd mean_shape() const override { return {}; }
    Eigen::MatrixX3d vertices(const Eigen::VectorXd&) const override { return {}; }
    Eigen::VectorXd solve(const BodyRequest&) const override { return {}; }
    std::pair<double, double> bmi_range() const override { return {10, 65}; }
    Eigen::MatrixX3i f;
  } plain;
  CHECK_THAT(test::message_of([&] { check_proportions(plain, "plain", BodyRequest{24, 1.75, 1, {{"chest", 0.1}}}); }),
             Catch::Contains("offers no proportions: BMI and height shape it"));
}
