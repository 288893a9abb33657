#pragma once
// Helpers for the plugin tests: nodes built by name through the build tree's
// registry (so the plugin libraries themselves are exercised), deterministic
// random tensors, a small garment with material-space UVs, and a one-shot forward.
#include <drape/energy.hpp>
#include <drape/assets/assets.hpp>
#include <drape/gradcheck.hpp>
#include <drape/plugin.hpp>

#include <functional>
#include <memory>
#include <random>
#include <string>

#include "test_support.hpp"

namespace drape::test {

inline Params params_for(const std::string& plugin, const std::string& yaml) {
  const PluginDescriptor& d = plugins().get(plugin);
  return Params(d.params, param_values_from_yaml(YAML::Load(yaml), "test.yaml"), plugin);
}

inline std::unique_ptr<Node> make_node(const std::string& plugin, const std::string& yaml = "{}") {
  return plugins().create_node(plugin, params_for(plugin, yaml));
}

// Finite differences across a kink of relu / leaky_relu (a pre-activation within
// one step of zero) measure the mean of the two slopes, not the gradient. Checks
// of piecewise-linear configurations therefore probe with a smaller step; the
// smooth (tanh) configurations cover the same wiring at the default step.
inline GradCheckOptions kink_safe() {
  GradCheckOptions o;
  o.step = 1e-4;
  return o;
}

inline Tensor random_tensor(int batch, int rows, int cols, std::uint64_t seed, float scale = 1.0f) {
  Tensor t(batch, rows, cols);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-scale, scale);
  for (std::size_t i = 0; i < t.size(); ++i) t.data()[i] = u(rng);
  return t;
}

// Sets the node up for the inputs' shapes, lets `prepare` adjust it (e.g. set
// weights by hand; setup re-initialises them), runs forward once and returns the outputs.
inline std::map<std::string, Tensor> run_forward(Node& node, const std::map<std::string, Tensor>& inputs,
                                                 const NodeContext& context = {},
                                                 const std::function<void(Node&)>& prepare = {}) {
  ShapeMap shapes;
  int batch = 0;
  TensorIn in;
  for (const auto& [k, t] : inputs) {
    shapes[k] = t.shape();
    batch = t.batch();
    in[k] = &t;
  }
  std::map<std::string, Tensor> outputs;
  TensorOut out;
  for (const auto& [k, s] : node.setup(shapes, context)) outputs[k] = Tensor(batch, s);
  for (auto& [k, t] : outputs) out[k] = &t;
  if (prepare) prepare(node);
  node.forward(in, out);
  return outputs;
}

// An n x n grid hanging in the XY plane (Y up), `spacing` meters apart, its
// material space equal to its rest (x, y); faces alternate between materials
// 0 and 1 when two are given.
inline std::shared_ptr<Garment> grid_garment(int n, double spacing, bool two_materials = false) {
  auto g = std::make_shared<Garment>();
  Mesh& m = g->mesh;
  m.vertices.resize(n * n, 3);
  m.uv.resize(n * n, 2);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.vertices.row(i * n + j) << j * spacing, 1.0 + i * spacing, 0.0;
      m.uv.row(i * n + j) << j * spacing, i * spacing;
    }
  m.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  m.uv_faces = m.faces;
  g->materials.push_back(Material{});
  g->materials[0].name = "knit";
  if (two_materials) {
    Material print;
    print.name = "print";
    print.density = 0.5;
    g->materials.push_back(print);
    g->face_material.resize(m.num_faces());
    for (int k = 0; k < m.num_faces(); ++k) g->face_material[k] = k % 2;
  }
  return g;
}

inline Assets assets_with(std::shared_ptr<const Garment> garment) {
  Assets a;
  a.garment = std::move(garment);
  return a;
}

// The skinning nodes' garment: a 2x2 grid (4 vertices) on two joints, vertex
// 0 all joint 0, vertex 1 all joint 1, vertices 2 and 3 a quarter / three
// quarters on joint 1.
inline Assets two_joint_skinned_assets() {
  Assets a = assets_with(grid_garment(2, 0.1));
  a.garment_skinning.resize(4, 2);
  a.garment_skinning << 1, 0, 0, 1, 0.25f, 0.75f, 0.75f, 0.25f;
  return a;
}

// Their transforms [batch, 2, 12]: joint 0 unturned, moved by `first_moved`;
// joint 1 turned 90 degrees about y (x -> -z, z -> x) and moved by (1, 2, 3),
// or (`second_turned` false) at rest like joint 0.
inline Tensor two_joint_transforms(int batch, Eigen::Vector3f first_moved = Eigen::Vector3f::Zero(),
                                   bool second_turned = true) {
  Tensor t(batch, 2, 12);
  const float rest[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, first_moved.x(), first_moved.y(), first_moved.z()};
  const float turned[12] = {0, 0, 1, 0, 1, 0, -1, 0, 0, 1, 2, 3};
  for (int s = 0; s < batch; ++s)
    for (int k = 0; k < 12; ++k) {
      t(s, 0, k) = rest[k];
      t(s, 1, k) = second_turned ? turned[k] : rest[k];
    }
  return t;
}

}  // namespace drape::test
