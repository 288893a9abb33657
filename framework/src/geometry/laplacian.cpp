#include <drape/geometry/laplacian.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <vector>

namespace drape::geometry {

Eigen::SparseMatrix<double, Eigen::RowMajor> graph_laplacian(const Eigen::MatrixX3i& faces, int num_vertices,
                                                             GraphLaplacian kind) {
  // Adjacency from the face edges; duplicates (an edge of two faces) collapse to 1.
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(6 * static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      t.emplace_back(a, b, 1.0);
      t.emplace_back(b, a, 1.0);
    }
  Eigen::SparseMatrix<double, Eigen::RowMajor> adj(num_vertices, num_vertices);
  adj.setFromTriplets(t.begin(), t.end(), [](double, double) { return 1.0; });

  t.clear();
  for (int i = 0; i < num_vertices; ++i) {
    const double degree = static_cast<double>(adj.outerIndexPtr()[i + 1] - adj.outerIndexPtr()[i]);
    if (degree == 0) continue;
    const double off = kind == GraphLaplacian::random_walk ? -1.0 / degree : -1.0;
    t.emplace_back(i, i, kind == GraphLaplacian::random_walk ? 1.0 : degree);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(adj, i); it; ++it) t.emplace_back(i, it.col(), off);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> lap(num_vertices, num_vertices);
  lap.setFromTriplets(t.begin(), t.end());
  return lap;
}

Eigen::SparseMatrix<double> cotangent_stiffness(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  const int n = static_cast<int>(vertices.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(12 * static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      // The angle at corner k faces the edge (i, j).
      const int o = faces(f, k), i = faces(f, (k + 1) % 3), j = faces(f, (k + 2) % 3);
      const Eigen::Vector3d a = vertices.row(i) - vertices.row(o), b = vertices.row(j) - vertices.row(o);
      const double sin2 = a.cross(b).norm();
      const double cot = sin2 > 0 ? std::clamp(a.dot(b) / sin2, -1e3, 1e3) : 0.0;
      const double w = 0.5 * cot;
      t.emplace_back(i, j, -w);
      t.emplace_back(j, i, -w);
      t.emplace_back(i, i, w);
      t.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(t.begin(), t.end());
  return k;
}

Eigen::VectorXd lumped_mass(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(vertices.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (int k = 0; k < 3; ++k) m[faces(f, k)] += third;
  }
  return m;
}

}  // namespace drape::geometry
