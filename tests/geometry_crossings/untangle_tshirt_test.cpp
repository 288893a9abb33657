// The untangle's search for crossings on the coarse T-shirt itself (sleeves,
// hem, collar, seams: a real garment's topology, where the hierarchy's nodes
// are cut through every shape of cloth), shaken by noise of growing size: it
// passes over the height fields it finds and must find exactly the pairs
// self_edge_crossings finds with its own grid and no hierarchy.
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/untangle.hpp>

#include <catch2/catch.hpp>

#include <random>

#include "../garments/tshirt_support.hpp"

TEST_CASE("untangle: on the coarse T-shirt shaken by noise the search finds every crossing self_edge_crossings finds") {
  const drape::Garment shirt = drape::test::build_tshirt("{resolution: coarse}");
  const Eigen::MatrixX3i& faces = shirt.mesh.faces;
  std::mt19937 random(11);
  int culled_somewhere = 0, crossed = 0;
  drape::geometry::Untangler untangler(faces, static_cast<int>(shirt.mesh.vertices.rows()));
  for (const double amplitude : {0.0, 0.002, 0.005, 0.01, 0.02, 0.04}) {
    std::normal_distribution<double> noise(0.0, amplitude);
    Eigen::MatrixX3d x = shirt.mesh.vertices;
    for (Eigen::Index v = 0; v < x.rows(); ++v)
      for (int k = 0; k < 3; ++k) x(v, k) += amplitude > 0 ? noise(random) : 0.0;
    const auto expected = drape::geometry::self_edge_crossings(x, faces, 1000000);
    drape::geometry::UntangleOptions options;
    options.max_rounds = 1;
    const auto report = untangler.run(x, options);
    INFO("noise " << amplitude << " m: " << expected.size() << " crossings, " << report.edges_culled << " edges culled");
    CHECK(report.crossings_before == static_cast<int>(expected.size()));
    crossed += !expected.empty();
    culled_somewhere += report.edges_culled > 0;
  }
  CHECK(crossed >= 3);            // the larger noises cross the cloth through itself
  CHECK(culled_somewhere >= 4);   // and the smaller leave height fields to pass over
}
