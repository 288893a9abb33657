#pragma once
// The fixed topology: the mean body meshed once, regularised, put in
// locality order and bound to the parts of the rig.
#include "body_plan.hpp"
#include "implicit_body.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::parametric {

struct BodyTemplate {
  Rig rig = Rig::Mannequin;
  ImplicitBody mean;            // the implicit body it was meshed from
  Eigen::MatrixX3d vertices;    // on the mean body's surface
  Eigen::MatrixX3i faces;
  std::vector<std::vector<int>> neighbours;
  // Up to four parts per vertex and their weights (summing to 1): a vertex
  // follows the parts whose surface it lies on.
  static constexpr int kBind = 4;
  std::vector<std::array<int, kBind>> bind_part;
  std::vector<std::array<double, kBind>> bind_weight;
};

// Builds the template (deterministic; a fraction of a second):
// mesh_template, then finish_template.
BodyTemplate build_template(int target_vertices = 6000, Rig rig = Rig::Mannequin);
// The costly part: meshes t.mean (of t.rig) into t.vertices and t.faces.
void mesh_template(BodyTemplate& t, int target_vertices);
// What follows from the mesh: neighbours and the binding to the parts.
void finish_template(BodyTemplate& t);

// Moves every vertex along the surface of `body` towards the mean of its
// neighbours, then back onto the surface: evens out triangle shapes.
void relax_on_surface(const ImplicitBody& body, const std::vector<std::vector<int>>& neighbours,
                      Eigen::MatrixX3d& vertices, int iterations, double step);

}  // namespace drape::parametric
