// The seed's metrics (drape/training/metrics.hpp) on the 300-vertex T-shirt: zero for
// the ground truth itself, and values worked out by hand for translations,
// scalings and a one-vertex bump.
#include <catch2/catch.hpp>

#include <drape/geometry/penetration.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/errors.hpp>
#include <drape/training/metrics.hpp>
#include <drape/plugin.hpp>

#include <set>

#include "train_test_util.hpp"

using namespace drape;

namespace {

struct Fixture {
  std::shared_ptr<const Assets> assets = test::tiny_assets();
  MetricsContext metrics{*assets};
  Eigen::MatrixX3d garment = assets->garment->mesh.vertices;
  Eigen::MatrixX3d body = assets->body.vertices;
};

}  // namespace

TEST_CASE("the ground truth scores zero on every metric but p", "[metrics]") {
  Fixture f;
  const GarmentMetrics m = f.metrics.evaluate(f.garment, f.garment, f.body);
  CHECK(m.me_cm == 0.0);
  CHECK(m.laplacian_cm == 0.0);
  CHECK(m.edge_percent == 0.0);
  CHECK(m.spectral == 0.0);
  CHECK(m.deformation == 0.0);
  const double p = geometry::penetration_ratio(geometry::BodySurface(f.body, f.assets->body.faces), f.garment);
  CHECK(m.penetration_percent == Approx(100.0 * p));
  // A garment on itself over the body: the fixture's drape, whose crossings the
  // independent count gives.
  const int crossings = geometry::surface_crossings(f.garment, f.assets->garment->mesh.faces, f.body, f.assets->body.faces).total();
  CHECK(m.crossings == crossings);
  CHECK(m.crossed_percent == (crossings > 0 ? 100.0 : 0.0));
  CHECK(m.edge_stretch_max == 0.0);
  REQUIRE(metric_columns().size() == 10);
  std::vector<std::string> names;
  for (const auto& c : metric_columns()) names.push_back(c.name);
  // The seed's six, then the surface crossings and the worst edge.
  CHECK(names ==
        std::vector<std::string>{"ME", "L_l", "L_e", "L_s", "L_d", "p", "crossings", "crossed_samples", "edge_stretch_max",
                                 "strain_max"});
}

TEST_CASE("a translation changes ME and L_s only", "[metrics]") {
  Fixture f;
  const Eigen::RowVector3d t(0.01, -0.02, 0.005);
  const Eigen::MatrixX3d x = f.garment.rowwise() + t;
  const GarmentMetrics m = f.metrics.evaluate(x, f.garment, f.body);
  CHECK(m.me_cm == Approx(100.0 * t.norm()));
  CHECK(m.laplacian_cm == Approx(0.0).margin(1e-9));  // Laplacian rows sum to zero
  CHECK(m.edge_percent == Approx(0.0).margin(1e-9));
  CHECK(m.deformation == Approx(0.0).margin(1e-9));
  // V^T (1 t) has rows (column sum of V_j) t: the mean of their L1 norms factorises.
  const Eigen::MatrixXd V = f.assets->eigenvectors.cast<double>();
  REQUIRE(V.cols() == test::kTinyK);
  const double expected = V.colwise().sum().cwiseAbs().mean() * t.cwiseAbs().sum();
  CHECK(m.spectral == Approx(expected).epsilon(1e-6));
  CHECK(m.spectral > 0.0);
}

TEST_CASE("a uniform scaling by s gives L_e = |s - 1| and L_d linear in s - 1", "[metrics]") {
  Fixture f;
  const Eigen::RowVector3d c = f.garment.colwise().mean();
  auto scaled = [&](double s) { return Eigen::MatrixX3d((c.replicate(f.garment.rows(), 1) + s * (f.garment.rowwise() - c))); };
  const GarmentMetrics m = f.metrics.evaluate(scaled(1.1), f.garment, f.body);
  CHECK(m.edge_percent == Approx(10.0).epsilon(1e-9));
  CHECK(m.me_cm == Approx(100.0 * 0.1 * (f.garment.rowwise() - c).rowwise().norm().mean()).epsilon(1e-9));
  const double ld_double = f.metrics.deformation_difference(scaled(2.0), f.garment);
  CHECK(m.deformation == Approx(0.1 * ld_double).epsilon(1e-9));
  // Doubling gives mean sum |F| of the rest garment: about 2 to 2 sqrt(3) for a near-isometric
  // dressing of the material space (each column of F a unit 3-vector).
  CHECK(ld_double > 1.5);
  CHECK(ld_double < 4.0);
}

TEST_CASE("L_l of a one-vertex bump: the bump and its share in each neighbour's mean", "[metrics]") {
  Fixture f;
  const Mesh& mesh = f.assets->garment->mesh;
  // A vertex that no coarser level keeps, so only level 0 sees the bump.
  std::set<int> coarse;
  for (int l = 1; l < f.assets->hierarchy.num_levels(); ++l)
    for (int i = 0; i < f.assets->hierarchy.levels[l].fine_index.size(); ++i) coarse.insert(f.assets->hierarchy.levels[l].fine_index[i]);
  int v = 0;
  while (coarse.count(v)) ++v;
  std::vector<std::set<int>> neighbours(static_cast<std::size_t>(mesh.num_vertices()));
  for (int face = 0; face < mesh.num_faces(); ++face)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(face, k), b = mesh.faces(face, (k + 1) % 3);
      neighbours[a].insert(b);
      neighbours[b].insert(a);
    }
  const Eigen::RowVector3d bump(0.01, -0.004, 0.0);
  Eigen::MatrixX3d x = f.garment;
  x.row(v) += bump;
  // (L d)_v = d_v; (L d)_j = -d_v / deg(j) for each neighbour j; mean over the level's vertices.
  double expected = bump.cwiseAbs().sum();
  for (int j : neighbours[v]) expected += bump.cwiseAbs().sum() / double(neighbours[j].size());
  expected /= mesh.num_vertices();
  CHECK(f.metrics.laplacian_difference(x, f.garment) == Approx(expected).epsilon(1e-9));
}

TEST_CASE("p counts garment vertices inside the body", "[metrics]") {
  Fixture f;
  const Eigen::RowVector3d c = f.body.colwise().mean();
  const Eigen::MatrixX3d shrunk = c.replicate(f.garment.rows(), 1) + 0.3 * (f.garment.rowwise() - c);
  CHECK(f.metrics.evaluate(shrunk, f.garment, f.body).penetration_percent > 50.0);
  const Eigen::MatrixX3d away = f.garment.rowwise() + Eigen::RowVector3d(0, 0, 2.0);
  CHECK(f.metrics.evaluate(away, f.garment, f.body).penetration_percent == 0.0);
}

TEST_CASE("metrics refuse wrong sizes and non-finite vertices, and summaries average", "[metrics]") {
  Fixture f;
  CHECK_THROWS_WITH(f.metrics.evaluate(f.garment.topRows(10), f.garment, f.body),
                    Catch::Contains("has 10 vertices, expected " + std::to_string(f.garment.rows())));
  CHECK_THROWS_WITH(f.metrics.evaluate(f.garment, f.garment, f.body.topRows(5)), Catch::Contains("the body has 5 vertices"));
  Eigen::MatrixX3d bad = f.garment;
  bad(3, 1) = NAN;
  CHECK_THROWS_WITH(f.metrics.evaluate(bad, f.garment, f.body), Catch::Contains("non-finite"));

  GarmentMetrics a, b;
  a.me_cm = 1.0;
  b.me_cm = 3.0;
  a.penetration_percent = 2.0;
  b.penetration_percent = 2.0;
  const MetricsSummary s = summarize({a, b});
  CHECK(s.samples == 2);
  CHECK(s.mean.me_cm == 2.0);
  CHECK(s.stddev.me_cm == Approx(std::sqrt(2.0)));
  CHECK(s.stddev.penetration_percent == 0.0);
  CHECK(s.max.me_cm == 3.0);  // the worst sample
  CHECK(s.max.penetration_percent == 2.0);
}

TEST_CASE("crossing summaries: mean per sample and the share of samples with any", "[metrics]") {
  // {0, 4, 0, 2}: mean 1.5, sample variance ((1.5^2 + 2.5^2 + 1.5^2 + 0.5^2) / 3) = 11/3;
  // crossed 0/1: {0, 1, 0, 1}, mean 0.5, variance (4 * 0.25) / 3 = 1/3.
  auto summary_of = [](std::vector<int> crossings) {
    std::vector<GarmentMetrics> samples;
    for (int c : crossings) {
      GarmentMetrics m;
      m.crossings = c;
      m.crossed_percent = c > 0 ? 100.0 : 0.0;
      samples.push_back(m);
    }
    return summarize(samples);
  };
  const MetricsSummary s = summary_of({0, 4, 0, 2});
  CHECK(s.mean.crossings == 1.5);
  CHECK(s.stddev.crossings == Approx(std::sqrt(11.0 / 3.0)));
  CHECK(s.mean.crossed_percent == 50.0);
  CHECK(s.stddev.crossed_percent == Approx(100 * std::sqrt(1.0 / 3.0)));
  const MetricsSummary none = summary_of({});
  CHECK(none.mean.crossings == 0.0);
  CHECK(none.mean.crossed_percent == 0.0);
  CHECK(summary_of({3}).stddev.crossings == 0.0);
}

TEST_CASE("L_e, L_l, L_s and L_d are the values of the loss plugins (reduction: mean)", "[metrics]") {
  Fixture f;
  // A smooth sway plus vertex noise, so that every metric is well away from zero.
  Eigen::MatrixX3d x = f.garment;
  Rng rng(9);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    x(i, 0) += 0.02 * std::sin(8.0 * f.garment(i, 1));
    for (int k = 0; k < 3; ++k) x(i, k) += rng.uniform(-0.003, 0.003);
  }
  Tensor pred(1, static_cast<int>(x.rows()), 3), target(1, static_cast<int>(x.rows()), 3);
  pred.mat(0) = x.cast<float>();
  target.mat(0) = f.garment.cast<float>();
  const NodeContext context{"loss", 1, f.assets.get(), {}};
  auto loss = [&](const std::string& type) {
    const PluginDescriptor& d = test::plugins().get(type);
    auto node = test::plugins().create_node(type, Params(d.params, {}, type));
    const ShapeMap shapes{{"pred", pred.shape()}, {"target", target.shape()}};
    node->setup(shapes, context);
    Tensor out(1, 1, 1);
    node->forward({{"pred", &pred}, {"target", &target}}, {{"loss", &out}});
    return double(out(0, 0, 0));
  };
  const Eigen::MatrixX3d xf = pred.mat(0).cast<double>(), yf = target.mat(0).cast<double>();  // what the losses see
  CHECK(f.metrics.edge_error(xf, yf) == Approx(loss("edge")).epsilon(1e-4));
  CHECK(f.metrics.laplacian_difference(xf, yf) == Approx(loss("laplacian")).epsilon(1e-4));
  CHECK(f.metrics.spectral_difference(xf, yf) == Approx(loss("spectral_loss")).epsilon(1e-4));
  CHECK(f.metrics.deformation_difference(xf, yf) == Approx(loss("deformation")).epsilon(1e-4));
}

TEST_CASE("edge_stretch_max is the most stretched edge against the ground truth", "[metrics]") {
  Fixture f;
  // Scaled by 1.1 about the origin every edge is 10 % longer; pulling one
  // vertex far away tears its edges: the worst is that of its shortest edge,
  // computed here from the mesh.
  CHECK(f.metrics.evaluate(1.1 * f.garment, f.garment, f.body).edge_stretch_max == Approx(10.0));
  CHECK(f.metrics.evaluate(0.9 * f.garment, f.garment, f.body).edge_stretch_max == Approx(0.0).margin(1e-9));  // shrinking stretches nothing
  Eigen::MatrixX3d torn = f.garment;
  const int v = 7;
  torn.row(v) += Eigen::RowVector3d(0.0, 0.0, 0.5);
  double expected = 0.0;
  const Eigen::MatrixX3i& faces = f.assets->garment->mesh.faces;
  for (Eigen::Index k = 0; k < faces.rows(); ++k)
    for (int j = 0; j < 3; ++j) {
      const int a = faces(k, j), b = faces(k, (j + 1) % 3);
      if (a != v && b != v) continue;
      const double before = (f.garment.row(a) - f.garment.row(b)).norm(), after = (torn.row(a) - torn.row(b)).norm();
      expected = std::max(expected, 100.0 * (after / before - 1.0));
    }
  REQUIRE(expected > 100.0);
  CHECK(f.metrics.evaluate(torn, f.garment, f.body).edge_stretch_max == Approx(expected));
}

TEST_CASE("strain_max is the most strained edge against the material space", "[metrics]") {
  // Computed here from the template's own UVs: each face's three edges, the
  // rest length that of the face's UV corners.
  Fixture f;
  const auto by_hand = [&](const Eigen::MatrixX3d& x) { return test::strain_by_hand(f.assets->garment->mesh, x); };
  const double placed = by_hand(f.garment);
  CHECK(f.metrics.evaluate(f.garment, f.garment, f.body).strain_max == Approx(placed));
  // Scaled by 1.5 every edge is 1.5 times as long: 1.5 (1 + s) - 1 = 0.5 + 1.5 s.
  CHECK(f.metrics.evaluate(1.5 * f.garment, f.garment, f.body).strain_max == Approx(50.0 + 1.5 * placed));
  Eigen::MatrixX3d torn = f.garment;
  torn.row(7) += Eigen::RowVector3d(0.0, 0.0, 0.5);
  const double expected = by_hand(torn);
  REQUIRE(expected > 100.0);
  CHECK(f.metrics.evaluate(torn, f.garment, f.body).strain_max == Approx(expected));
  CHECK(f.metrics.strain_max(torn) == Approx(expected / 100.0));
}

TEST_CASE("strain_max against the garment a body wore: its own rest lengths", "[metrics]") {
  // A garment of the template's topology graded to twice its size (its
  // material space doubled): a drape twice the template's placed shape is
  // as strained against it as the placed shape is against the template.
  Fixture f;
  Mesh graded = f.assets->garment->mesh;
  graded.uv *= 2.0;
  const std::vector<double> rest = face_edge_rest_lengths(graded);
  REQUIRE(rest.size() == 3 * static_cast<std::size_t>(graded.faces.rows()));
  const Eigen::Index face = 5;
  CHECK(rest[3 * face + 1] == Approx(2.0 * (f.assets->garment->mesh.uv.row(f.assets->garment->mesh.uv_faces(face, 2)) -
                                            f.assets->garment->mesh.uv.row(f.assets->garment->mesh.uv_faces(face, 1)))
                                               .norm()));
  const double placed = f.metrics.strain_max(f.garment);
  CHECK(f.metrics.evaluate(2.0 * f.garment, f.garment, f.body, &rest).strain_max == Approx(100.0 * placed));
  // The same drape against the template: every edge twice as long, 2 (1 + s) - 1.
  CHECK(f.metrics.evaluate(2.0 * f.garment, f.garment, f.body).strain_max == Approx(100.0 + 200.0 * placed));
  // The placed shape itself is at half its graded rest: (1 + s) / 2 - 1.
  CHECK(f.metrics.strain_max(f.garment, &rest) == Approx((1.0 + placed) / 2.0 - 1.0));
  const std::vector<double> short_list(rest.begin(), rest.end() - 1);
  CHECK_THROWS_WITH(f.metrics.strain_max(f.garment, &short_list), Catch::Contains("rest lengths for a garment of"));
  Mesh no_uv = graded;
  no_uv.uv.resize(0, 2);
  CHECK_THROWS_AS(face_edge_rest_lengths(no_uv), ConfigError);
}
