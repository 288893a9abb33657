#pragma once
// "[rows, cols]": how the nn kernels name a matrix's shape in their errors.
#include <Eigen/Core>

#include <string>

namespace drape::nn {

inline std::string dims(Eigen::Index r, Eigen::Index c) { return "[" + std::to_string(r) + ", " + std::to_string(c) + "]"; }

}  // namespace drape::nn
