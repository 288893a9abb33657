#pragma once
// Quadric-error half-edge collapses that keep boundaries, UV seams and charts
// (the engine behind build_hierarchy). Private to the framework.
#include <drape/geometry/hierarchy.hpp>

#include <Eigen/Core>

#include <array>
#include <queue>
#include <vector>

namespace drape::geometry::detail {

class EdgeCollapser {
 public:
  EdgeCollapser(const Mesh& mesh, const HierarchyOptions& options);

  // Collapses the cheapest allowed edges until at most `target` vertices are
  // left or no allowed collapse remains. Returns the number of vertices left.
  int collapse_until(int target);
  int num_vertices() const { return alive_count_; }

  // The current mesh with compact indices; `vertex_index` and `uv_index` give
  // each vertex / UV's index in the input mesh (both increasing), `face_chart`
  // the input's UV chart of each face.
  void extract(Mesh& out, Eigen::VectorXi& vertex_index, Eigen::VectorXi& uv_index, Eigen::VectorXi& face_chart) const;

 private:
  struct Candidate {
    double cost;
    int u, v;     // collapse u into v
    int su, sv;   // stamps of u and v when the cost was computed
    bool operator>(const Candidate& o) const { return cost > o.cost; }
  };
  using UvMap = std::vector<std::pair<int, int>>;  // (face of u, UV its u corner takes)

  int corner(int f, int a) const;
  std::vector<int> neighbours(int a) const;
  std::vector<int> edge_faces(int a, int b) const;
  bool is_feature_edge(int a, int b) const;
  std::vector<int> feature_neighbours(int a) const;
  double cost(int u, int v) const;
  bool plan(int u, int v, UvMap& map) const;
  void collapse(int u, int v, const UvMap& map);
  void push_around(int v);
  void push(int u, int v);

  HierarchyOptions opt_;
  Eigen::MatrixX3d pos_;
  Eigen::MatrixX2d uv_;
  std::vector<std::array<int, 3>> fv_, fuv_;
  std::vector<char> face_alive_;
  std::vector<int> chart_;  // UV chart of each face in the input (faces keep theirs)
  std::vector<std::vector<int>> vf_;  // vertex -> alive incident faces
  std::vector<char> vertex_alive_, fixed_;
  std::vector<Eigen::Matrix4d> quadric_;
  std::vector<double> quadric_area_;
  std::vector<int> stamp_;
  int alive_count_ = 0;
  double cos_max_turn_ = 0.5;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> heap_;
};

}  // namespace drape::geometry::detail
