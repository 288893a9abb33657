// The T-shirt's sizes as a scene dresses them (docs/garments.md, "Sizes"):
// each on its fit body (drape/bodies/fit_body.hpp), placed around that body's
// torso frame, and none passing through itself, at the coarse and the default
// resolution. The crossing count is geometry::self_intersections (a
// triangle-triangle test sharing no code with the placement or the dressing;
// touching counts as crossing, so it is stricter than
// scripts/count_self_crossings.py, which docs/garments.md reports).
#include "tshirt_support.hpp"

#include <drape/bodies/fit_body.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/scene/garment_size.hpp>

#include <catch2/catch.hpp>

#include <memory>
#include <sstream>
#include <string>

using namespace drape;

TEST_CASE("sizes: every size, coarse and default, dressed on its fit body without passing through itself",
          "[garments][tshirt][sizes]") {
  const auto model = test::parametric_body();
  std::string summary;
  for (const char* resolution : {"coarse", "default"})
    for (const char* size : {"3xsmall", "2xsmall", "xsmall", "small", "regular", "large", "xlarge", "2xlarge", "3xlarge", "4xlarge", "5xlarge", "6xlarge"}) {
      INFO(size << ", " << resolution);
      Garment g = test::build_tshirt(std::string("{size: ") + size + ", resolution: " + resolution + "}");
      const FitBody body = dress_on_fit_body(*model, g, size);
      const std::size_t crossings = geometry::self_intersections(g.mesh.vertices, g.mesh.faces, 1000).size();
      CHECK(crossings == 0);
      // Worn, not a tent: every vertex within 16 cm of its body (the 6xlarge's
      // fit body is the largest the body model reaches, 1.835 of the mean
      // girth, so it hangs 9 % looser than its design), the hem above the
      // knees (y 0.50 on the bodies of 1.75 m), the collar at the neck.
      const geometry::BodySurface surface(body.vertices, model->faces());
      const Eigen::VectorXd d = surface.signed_distances(g.mesh.vertices);
      std::ostringstream row;
      row << "\n  " << size << ", " << resolution << ": farthest vertex " << d.maxCoeff() << " m from its fit body, hem at y "
          << g.mesh.vertices.col(1).minCoeff();
      summary += row.str();
      CHECK(d.minCoeff() > 0.0);
      CHECK(d.maxCoeff() < (std::string(size) == "6xlarge" ? 0.16 : 0.13));
      CHECK(g.mesh.vertices.col(1).minCoeff() > 0.58);
      CHECK(g.mesh.vertices.col(1).maxCoeff() == Approx(1.52).margin(0.02));
    }
  WARN("the sizes on their fit bodies:" << summary);
}

TEST_CASE("sizes: a size's girth on the mean body's band is its grade times the regular's", "[garments][tshirt][sizes]") {
  const auto model = test::parametric_body();
  const Eigen::MatrixX3d mean = model->vertices(model->mean_shape());
  auto girth = [&](const std::string& size) {
    Garment g = test::build_tshirt("{size: " + size + ", resolution: coarse}");
    dress_on_fit_body(*model, g, size);
    return garment_girth(g.mesh.vertices, g.mesh.faces, mean);
  };
  const double regular = girth("regular");
  for (const auto& [size, grade] : {std::pair<std::string, double>{"3xsmall", 0.6}, {"xsmall", 0.8}, {"small", 0.9}, {"xlarge", 1.25}, {"4xlarge", 1.7}, {"6xlarge", 2.0}}) {
    INFO(size);
    CHECK(girth(size) / regular == Approx(grade).epsilon(0.02));
  }
}

TEST_CASE("dress untangles a garment its pushes folded through itself", "[garments][dressing][sizes]") {
  // The small shirt's armpits sit in the creases of its fit body's: pushed
  // out vertex by vertex, neighbours land on the arm and on the torso and the
  // cloth folds through itself (34 edges through faces at the default resolution).
  const auto model = test::parametric_body();
  const Garment placed = test::build_tshirt("{size: small}");
  const FitBody body = fit_body(*model, placed.fit_grade);
  const Mesh mesh{body.vertices, model->faces(), {}, {}};
  Garment plain = placed;
  DressOptions no_untangling;
  no_untangling.untangle_rounds = 0;
  dress(plain, mesh, no_untangling);
  const std::size_t folded = geometry::self_edge_crossings(plain.mesh.vertices, plain.mesh.faces, 1000).size();
  WARN("small shirt, pushes only: " << folded << " edges through faces, "
                                    << geometry::self_intersections(plain.mesh.vertices, plain.mesh.faces, 1000).size()
                                    << " face pairs through each other");
  REQUIRE(folded > 0);
  Garment untangled = placed;
  const DressReport r = dress(untangled, mesh);
  CHECK(r.tangled_before == static_cast<int>(folded));
  CHECK(r.tangled_after == 0);
  CHECK(r.untangle_rounds > 0);
  CHECK(geometry::self_edge_crossings(untangled.mesh.vertices, untangled.mesh.faces, 1000).empty());
  CHECK(geometry::self_intersections(untangled.mesh.vertices, untangled.mesh.faces, 1000).empty());
  CHECK(r.min_distance_after >= 0.01 - 2e-6);  // still clear of the body
  // A garment the pushes left untangled is not touched again: the regular on the mean body.
  Garment regular = test::build_tshirt();
  const Mesh mean{model->vertices(model->mean_shape()), model->faces(), {}, {}};
  Garment regular_plain = regular;
  dress(regular_plain, mean, no_untangling);
  const DressReport rr = dress(regular, mean);
  CHECK(rr.tangled_before == 0);
  CHECK(regular.mesh.vertices == regular_plain.mesh.vertices);
}

TEST_CASE("self_edge_crossings sees a fold one edge long that self_intersections skips", "[geometry][sizes]") {
  // Edge 0-1 runs along the z axis through the face (2, 3, 4) around the
  // origin in z = 0; its one face (0, 1, 3) shares vertex 3 with the pierced
  // face, so self_intersections (which skips faces sharing a vertex) does not
  // compare them; the edge itself shares no vertex with the face, so it counts.
  Eigen::MatrixX3d v(5, 3);
  v << 0, 0, -1, 0, 0, 1, -0.5, -0.5, 0, 0.5, -0.5, 0, 0, 0.8, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 3,  // the edge's face, through the pierced face's corner 3
      2, 3, 4;   // the pierced face
  CHECK(geometry::self_intersections(v, f).empty());
  const auto crossings = geometry::self_edge_crossings(v, f);
  REQUIRE(crossings.size() == 1);
  CHECK(crossings[0].first == std::make_pair(0, 1));
  CHECK(crossings[0].second == 1);
}
