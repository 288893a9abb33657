// The T-shirt template under the barrier contact: a barrier keeps separated
// surfaces apart but cannot pull crossing ones apart, so every shipped size
// must start clear of the body it starts on (its fit body: the mean body for
// the regular, fit_body.hpp), or be freed by the simulation's small
// start-body shrink (1 cm at most, docs/scenes.md). Checked with tools that
// share no code with the placement or the contact: the exact crossing count
// and the generalised winding number of each garment vertex, against the
// start body shrunk 1 cm along its own vertex normals, computed here.
#include <drape/geometry/surface_crossings.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <catch2/catch.hpp>

#include <string>

#include "../geometry_queries/reference.hpp"
#include "test_support.hpp"

using namespace drape;

namespace {

// Area-weighted vertex normals of a closed counter-clockwise mesh.
Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& faces) {
  Eigen::MatrixX3d n = Eigen::MatrixX3d::Zero(v.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = v.row(faces(f, 0)), b = v.row(faces(f, 1)), c = v.row(faces(f, 2));
    const Eigen::Vector3d area_normal = (b - a).cross(c - a);  // twice the area, outward
    for (int k = 0; k < 3; ++k) n.row(faces(f, k)) += area_normal.transpose();
  }
  return n.rowwise().normalized();
}

}  // namespace

TEST_CASE("tshirt: every size starts clear of its start body shrunk by 1 cm, so a barrier run can begin",
          "[barrier][garments][tshirt]") {
  const auto size = GENERATE(as<std::string>{}, "3xsmall", "2xsmall", "xsmall", "small", "regular", "large", "xlarge", "2xlarge", "3xlarge", "4xlarge",
                             "5xlarge", "6xlarge");
  const Scene scene = parse_scene("body: {model: parametric}\ngarment: {template: tshirt, params: {size: " + size +
                                  ", resolution: coarse}}\neffects: {gravity: {}, barrier: {}}\n");
  const Simulation sim(test::plugins(), scene);
  const Eigen::MatrixX3d& garment = sim.garment().mesh.vertices;
  const Eigen::MatrixX3i& body_faces = sim.body_model().faces();
  Mesh shrunk;
  shrunk.vertices = sim.fit_body() - 0.01 * vertex_normals(sim.fit_body(), body_faces);
  shrunk.faces = body_faces;
  INFO("size " << size << ": " << garment.rows() << " garment vertices");
  // A closed, outward body of a person's volume: the 3xsmall's fit body is
  // the mean body's height at BMI 11.1 (34 kg, about 0.033 m^3), 1 cm thinner.
  REQUIRE(test::signed_volume(shrunk) > 0.015);

  const geometry::SurfaceCrossings c = geometry::surface_crossings(garment, sim.garment().mesh.faces, shrunk.vertices, body_faces);
  CHECK(c.garment_edges_through_body == 0);
  CHECK(c.body_edges_through_garment == 0);
  int inside = 0;
  for (Eigen::Index v = 0; v < garment.rows(); ++v) inside += test::winding_number(shrunk, garment.row(v)) > 0.5;
  CHECK(inside == 0);
}
