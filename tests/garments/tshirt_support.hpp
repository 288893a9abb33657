#pragma once
// Shared by the T-shirt tests: building the template through the registry and
// reading its two UV charts back.
#include <drape/energy.hpp>
#include <drape/bodies/body.hpp>
#include <drape/params.hpp>

#include <test_support.hpp>

#include <string>
#include <vector>

namespace drape::test {

inline Garment build_tshirt(const std::string& yaml = "{}") {
  const PluginDescriptor& d = plugins().get("tshirt");
  return plugins().create_garment("tshirt", Params(d.params, param_values_from_yaml(YAML::Load(yaml), "test"), "tshirt"))->build();
}

// Chart (0 = front, 1 = back) of each face: faces sharing a UV index are in one
// chart; the front is the chart holding the smallest u (the documented layout).
inline std::vector<int> uv_chart_of_faces(const Mesh& mesh) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.uv.rows()));
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (Eigen::Index f = 0; f < mesh.uv_faces.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[find(mesh.uv_faces(f, k))] = find(mesh.uv_faces(f, 0));
  Eigen::Index leftmost = 0;
  mesh.uv.col(0).minCoeff(&leftmost);
  const int front_root = find(static_cast<int>(leftmost));
  std::vector<int> chart(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) chart[f] = find(mesh.uv_faces(f, 0)) == front_root ? 0 : 1;
  return chart;
}

}  // namespace drape::test
