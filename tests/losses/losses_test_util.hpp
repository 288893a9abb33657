#pragma once
// Helpers of the loss and decoder tests: tensors from Eigen matrices, a cube
// body (closest points by hand), and the coarse T-shirt's template data.
#include <drape/energy.hpp>
#include <drape/bodies/body.hpp>
#include <drape/assets/assets.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/hierarchy.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/spectral/spectral.hpp>
#include <drape/tensor.hpp>

#include <memory>
#include <vector>

#include "../plugins/plugin_test_util.hpp"

namespace drape::test {

inline Tensor tensor_of(const std::vector<Eigen::MatrixX3d>& samples) {
  Tensor t(static_cast<int>(samples.size()), static_cast<int>(samples.front().rows()), 3);
  for (std::size_t b = 0; b < samples.size(); ++b) t.mat(static_cast<int>(b)) = samples[b].cast<float>();
  return t;
}

inline Tensor tensor_of(const Eigen::MatrixX3d& m) { return tensor_of(std::vector<Eigen::MatrixX3d>{m}); }

inline Eigen::MatrixX3d rows3(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixX3d m(static_cast<Eigen::Index>(rows.size()), 3);
  int r = 0;
  for (const auto& row : rows) {
    int c = 0;
    for (double v : row) m(r, c++) = v;
    ++r;
  }
  return m;
}

// The cube [-h, h]^3 as 12 triangles, counter-clockwise seen from outside.
inline Mesh cube_body(double h = 1.0) {
  Mesh m;
  m.vertices.resize(8, 3);
  m.vertices << -h, -h, -h, h, -h, -h, h, h, -h, -h, h, -h, -h, -h, h, h, -h, h, h, h, h, -h, h, h;
  m.faces.resize(12, 3);
  m.faces << 0, 1, 5, 0, 5, 4,  // y = -h
      3, 7, 6, 3, 6, 2,         // y = +h
      4, 5, 6, 4, 6, 7,         // z = +h
      0, 3, 2, 0, 2, 1,         // z = -h
      1, 2, 6, 1, 6, 5,         // x = +h
      0, 4, 7, 0, 7, 3;         // x = -h
  return m;
}

// Assets holding only a body mesh (what the v2v and direction losses read).
inline std::shared_ptr<Assets> body_assets(const Mesh& body) {
  auto a = std::make_shared<Assets>();
  a->body = body;
  return a;
}

// The coarse T-shirt (~1k vertices, two UV charts) as the template plugin makes
// it, with its 4-level hierarchy, random-walk Laplacians and 32 eigenvectors:
// what build_assets computes for the losses, without the body and the dressing
// (which these tests do not need), built once per test program.
inline const Assets& coarse_tshirt() {
  static const Assets assets = [] {
    Assets a;
    auto garment = std::make_shared<Garment>(
        plugins().create_garment("tshirt", params_for("tshirt", "{resolution: coarse}"))->build());
    a.hierarchy = geometry::build_hierarchy(garment->mesh);
    for (const auto& level : a.hierarchy.levels)
      a.laplacians.push_back(geometry::graph_laplacian(level.mesh.faces, level.mesh.num_vertices()).cast<float>());
    const Eigenbasis basis = compute_eigenbasis(garment->mesh, 32);
    a.eigenvalues = basis.values;
    a.eigenvectors = basis.vectors.cast<float>();
    a.garment = std::move(garment);
    return a;
  }();
  return assets;
}

}  // namespace drape::test
