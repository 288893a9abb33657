// Graph and cotangent Laplacians: row sums, symmetry, positivity, linear precision.
#include "../hierarchy/sewn_tube.hpp"

#include <drape/geometry/laplacian.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace drape;
using namespace drape::geometry;

namespace {

// A flat jittered grid in the plane z = 0 (interior points off the lattice).
Mesh flat_grid(int size) {
  Mesh m;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  m.vertices.resize(size * size, 3);
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) {
      const bool edge = r == 0 || c == 0 || r == size - 1 || c == size - 1;
      m.vertices.row(r * size + c) << c + (edge ? 0 : jitter(rng)), r + (edge ? 0 : jitter(rng)), 0.0;
    }
  m.faces.resize(2 * (size - 1) * (size - 1), 3);
  int f = 0;
  for (int r = 0; r + 1 < size; ++r)
    for (int c = 0; c + 1 < size; ++c) {
      const int a = r * size + c, b = a + 1, d = a + size, e = d + 1;
      m.faces.row(f++) << a, b, e;
      m.faces.row(f++) << a, e, d;
    }
  return m;
}

template <class Sparse>
double asymmetry(const Sparse& a) {
  const Eigen::MatrixXd d = Eigen::MatrixXd(a);
  return (d - d.transpose()).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("the random-walk graph Laplacian is I - D^-1 A") {
  const Mesh m = test::sewn_tube(8, 6);
  const auto L = graph_laplacian(m.faces, m.num_vertices());
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.num_vertices());
  CHECK((L * ones).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((Eigen::VectorXd(L.diagonal()).array() == 1.0).all());
  // On a tube every vertex has 4 to 6 neighbours, each weighted 1/degree.
  for (int i = 0; i < L.outerSize(); ++i)
    for (decltype(L)::InnerIterator it(L, i); it; ++it)
      if (it.col() != i) CHECK(it.value() == Approx(-1.0 / (L.row(i).nonZeros() - 1)));
}

TEST_CASE("the combinatorial graph Laplacian is symmetric with zero row sums") {
  const Mesh m = test::sewn_tube(8, 6);
  const auto L = graph_laplacian(m.faces, m.num_vertices(), GraphLaplacian::combinatorial);
  CHECK(asymmetry(L) == 0.0);
  CHECK((L * Eigen::VectorXd::Ones(m.num_vertices())).cwiseAbs().maxCoeff() == 0.0);
  CHECK(L.diagonal().minCoeff() >= 3);
}

TEST_CASE("a vertex in no face gets a zero row") {
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 2;
  const auto L = graph_laplacian(faces, 4);
  CHECK(L.row(3).nonZeros() == 0);
}

TEST_CASE("the cotangent stiffness is symmetric PSD and exact on linear functions") {
  const Mesh grid = flat_grid(12);
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(grid.vertices, grid.faces);
  CHECK(asymmetry(K) < 1e-12);
  CHECK((K * Eigen::VectorXd::Ones(grid.num_vertices())).cwiseAbs().maxCoeff() < 1e-12);
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x(grid.num_vertices());
    for (auto& v : x) v = normal(rng);
    CHECK(x.dot(K * x) >= 0);
  }
  // Linear precision: K times a linear function vanishes at interior vertices
  // of a flat mesh, whatever the triangle shapes.
  const Eigen::VectorXd linear = 2.0 * grid.vertices.col(0) - 0.7 * grid.vertices.col(1);
  const Eigen::VectorXd k_linear = K * linear;
  for (int r = 1; r < 11; ++r)
    for (int c = 1; c < 11; ++c) CHECK(std::abs(k_linear[r * 12 + c]) < 1e-10);
  // The Dirichlet energy of the linear function is |grad|^2 times the area.
  CHECK(0.5 * linear.dot(K * linear) == Approx((4.0 + 0.49) * 11 * 11 / 2.0).epsilon(1e-9));
}

TEST_CASE("the lumped mass adds up to the area") {
  const Mesh grid = flat_grid(6);
  CHECK(lumped_mass(grid.vertices, grid.faces).sum() == Approx(25.0));
}
