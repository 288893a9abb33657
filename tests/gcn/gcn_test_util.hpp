#pragma once
// Small hand-made assets for the graph-convolution plugins: a garment grid with
// UVs and its hierarchy, a body grid in row-major vertex order (consecutive
// indices are neighbours, like the body models' order), and an orthonormal
// stand-in for the eigenbasis. Plus dense reference matrices built straight
// from the definitions, independent of the sparse code under test.
#include <drape/energy.hpp>
#include <drape/assets/assets.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/hierarchy.hpp>

#include <Eigen/QR>

#include <cmath>
#include <memory>

#include "../plugins/plugin_test_util.hpp"

namespace drape::test {

using DenseF = Eigen::MatrixXf;

// Garment: an n x n grid (1.5 cm spacing) with `levels` hierarchy levels.
// Body: an m x m grid. Eigenvectors: k orthonormal columns over the garment.
inline std::shared_ptr<Assets> gcn_assets(int garment_n = 10, int levels = 4, int body_m = 7, int k = 6) {
  auto a = std::make_shared<Assets>();
  auto garment = grid_garment(garment_n, 0.015);
  a->garment = garment;
  geometry::HierarchyOptions options;
  options.levels = levels;
  a->hierarchy = geometry::build_hierarchy(garment->mesh, options);
  a->body = grid_garment(body_m, 0.05)->mesh;
  const int ng = garment->mesh.num_vertices();
  const Eigen::MatrixXd random = random_tensor(1, ng, k, 99).mat(0).cast<double>();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random);
  a->eigenvectors = (qr.householderQ() * Eigen::MatrixXd::Identity(ng, k)).cast<float>();
  a->eigenvalues = Eigen::VectorXd::LinSpaced(k, 0.0, 1.0);
  return a;
}

inline geometry::HierarchyLevel const& level(const Assets& a, int l) { return a.hierarchy.levels[std::size_t(l)]; }
inline int vertices_of(const Assets& a, int l) { return level(a, l).mesh.num_vertices(); }

// The 1-ring + self aggregation with the given values in row-major order
// (columns ascending, the vertex itself in its sorted place).
inline DenseF dense_ring(const Mesh& mesh, const float* values) {
  const auto nbrs = geometry::vertex_neighbours(mesh.faces, mesh.num_vertices());
  const int n = mesh.num_vertices();
  DenseF a = DenseF::Zero(n, n);
  int k = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<int> cols = nbrs[std::size_t(i)];
    cols.push_back(i);
    std::sort(cols.begin(), cols.end());
    for (int j : cols) a(i, j) = values[k++];
  }
  return a;
}

// Kipf & Welling's D^-1/2 (A + I) D^-1/2, dense.
inline DenseF dense_kipf(const Mesh& mesh) {
  const int n = mesh.num_vertices();
  DenseF a = DenseF::Identity(n, n);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) a(mesh.faces(f, c), mesh.faces(f, (c + 1) % 3)) = a(mesh.faces(f, (c + 1) % 3), mesh.faces(f, c)) = 1;
  const Eigen::VectorXf d = a.rowwise().sum().cwiseInverse().cwiseSqrt();
  return d.asDiagonal() * a * d.asDiagonal();
}

inline DenseF activate_dense(DenseF z, const std::string& kind) {
  if (kind == "tanh") return z.array().tanh().matrix();
  if (kind == "relu") return z.cwiseMax(0.0f);
  return z;
}

// Sample b of a tensor as a dense column-major matrix.
inline DenseF dense_of(const Tensor& t, int b) { return DenseF(t.mat(b)); }
inline DenseF weight_of(const Node& n, const std::string& name) { return DenseF(n.weights().at(name).value.mat(0)); }
inline Eigen::RowVectorXf bias_of(const Node& n, const std::string& name) {
  return n.weights().at(name).value.mat(0).row(0);
}

// Overwrites every weight of `node` with values in [-scale, scale] (from its own seed).
inline void randomise_weights(Node& node, std::uint64_t seed, float scale = 0.5f) {
  for (auto& [name, w] : node.weights()) {
    const Tensor r = random_tensor(1, w.value.rows(), w.value.cols(), seed++, scale);
    w.value.vec() = r.vec();
  }
}

}  // namespace drape::test
