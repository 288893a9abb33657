#pragma once
// Where a body mesh passes through itself, in words a user can look up. The
// scene refuses such a body under the garment (it has no inside there);
// `drape body` warns about one anywhere.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape {

// "2 pairs of its faces cross (12 body vertices around (...) m, heights
// 1.263-1.288 m (vertex 1332, ...))", or "" when none does. With `considered`
// (one flag per face), only pairs with at least one flagged face count.
std::string describe_self_intersections(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces,
                                        const std::vector<char>* considered = nullptr);

}  // namespace drape
