#pragma once
// Where on the garment something happens, in words a user can look up: how
// many vertices, their centre and heights, and the first few indices.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::scene_detail {

// "12 garment vertices around (0.10, 1.32, 0.02) m, heights 1.28-1.36 m (vertex 401, ...)", then
// ", 8 more around (-0.10, 1.32, 0.02) m (vertex 77)" for each other place (vertices more than
// 5 cm from the first place's), the largest first;
// `surface` names whose vertices they are ("body" for a place on the body).
std::string describe_region(const Eigen::MatrixX3d& x, const std::vector<int>& vertices, const char* surface = "garment");

}  // namespace drape::scene_detail
