// The energies on the T-shirt template: every face and hinge is used (no
// degenerate material space), hinges run across the side and shoulder seams
// (where the front and back UV charts meet), and the dressed state gives finite
// energies and derivatives.
#include <drape/energy.hpp>
#include <catch2/catch.hpp>

#include <map>
#include <utility>

#include "../garments/tshirt_support.hpp"
#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("stretching and bending bind to the T-shirt and use all of it", "[stretching][bending][tshirt]") {
  const Garment garment = build_tshirt();
  const Mesh& mesh = garment.mesh;
  // Interior edges counted independently: edges of two faces; and those whose faces lie in different UV charts.
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  const std::vector<int> chart = uv_chart_of_faces(mesh);
  std::size_t interior = 0, across_charts = 0, non_manifold = 0;
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() > 2) ++non_manifold;
    if (faces.size() == 2) {
      ++interior;
      if (chart[faces[0]] != chart[faces[1]]) ++across_charts;
    }
  }
  REQUIRE(non_manifold == 0);
  CHECK(across_charts > 0);

  CerrCapture cerr;
  const auto stretching = bound_energy("stretching", "{}", garment);
  const auto bending = bound_energy("bending", "{}", garment);
  const auto bending_from_rest = bound_energy("bending", "{rest: initial}", garment);
  CHECK(cerr.str().empty());  // nothing skipped

  const Eigen::MatrixX3d& x = mesh.vertices;
  Triplets t;
  stretching->add_hessian(x, t, true);
  CHECK(t.size() == 81 * static_cast<std::size_t>(mesh.num_faces()));
  t.clear();
  bending->add_hessian(x, t, true);
  CHECK(t.size() == 144 * interior);

  for (const Energy* e : {stretching.get(), bending.get()}) {
    const double value = e->value(x);
    CHECK(std::isfinite(value));
    CHECK(value > 0.0);  // dressing bends the flat panels and strains them a little
    CHECK(gradient_of(*e, x).allFinite());
  }
  CHECK(bending_from_rest->value(x) == 0.0);
}
