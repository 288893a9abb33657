// The writers element energies share: the lower-triangle form sums to exactly
// the lower triangle of the full form, for any vertex order within an element,
// repeated (degenerate) vertices included, and always writes the same count.
#include <drape/element_assembly.hpp>

#include <Eigen/SparseCore>

#include <catch2/catch.hpp>

#include <random>

using namespace drape;

namespace {

template <int N>
Eigen::MatrixXd summed(const Triplets& t, int vertices) {
  Eigen::SparseMatrix<double> m(3 * vertices, 3 * vertices);
  m.setFromTriplets(t.begin(), t.end());
  return Eigen::MatrixXd(m);
}

template <int N>
void check_lower_writer(const int (&vertex)[N], std::mt19937_64& rng) {
  constexpr int kDofs = 3 * N;
  std::normal_distribution<double> g;
  Eigen::Matrix<double, kDofs, kDofs> a;
  for (int i = 0; i < kDofs; ++i)
    for (int j = 0; j < kDofs; ++j) a(i, j) = g(rng);
  const Eigen::Matrix<double, kDofs, kDofs> h = a + a.transpose();  // element Hessians are symmetric
  Triplets full(9 * N * N), lower(kLowerEntries<N>);
  write_hessian_blocks<N>(h, vertex, full.data());
  write_lower_hessian_blocks<N>(h, vertex, lower.data());
  for (const auto& t : lower) CHECK(t.row() >= t.col());
  const int vertices = 8;
  const Eigen::MatrixXd expected = summed<N>(full, vertices).template triangularView<Eigen::Lower>();
  CHECK((summed<N>(lower, vertices) - expected).cwiseAbs().maxCoeff() <= 1e-14 * h.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("the lower-triangle Hessian writer sums to the lower triangle of the full writer's matrix") {
  std::mt19937_64 rng(5);
  STATIC_REQUIRE(kLowerEntries<3> == 45);
  STATIC_REQUIRE(kLowerEntries<4> == 78);
  SECTION("faces in every corner order") {
    const int orders[6][3] = {{0, 3, 7}, {0, 7, 3}, {3, 0, 7}, {3, 7, 0}, {7, 0, 3}, {7, 3, 0}};
    for (const auto& o : orders) check_lower_writer<3>(o, rng);
  }
  SECTION("hinges, increasing, decreasing and mixed") {
    const int hinges[3][4] = {{1, 2, 4, 6}, {6, 4, 2, 1}, {4, 1, 6, 2}};
    for (const auto& h : hinges) check_lower_writer<4>(h, rng);
  }
  SECTION("degenerate elements that name a vertex twice") {
    const int face[3] = {5, 2, 5};
    check_lower_writer<3>(face, rng);
    const int hinge[4] = {3, 3, 1, 3};
    check_lower_writer<4>(hinge, rng);
  }
}
