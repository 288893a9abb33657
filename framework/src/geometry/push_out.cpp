#include <drape/geometry/push_out.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace drape::geometry {
namespace {

constexpr double kRounding = 1e-12;  // m

}  // namespace

PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices, double margin, int max_passes,
                       std::vector<int>* closest_faces) {
  if (!(margin >= 0) || !std::isfinite(margin)) throw Error("push_out: the margin must be finite and >= 0");
  if (max_passes < 1) throw Error("push_out: at least one pass");
  if (!vertices.allFinite()) throw Error("push_out: the garment has a non-finite vertex");
  PushOutReport report;
  const Eigen::MatrixX3d start = vertices;
  std::vector<char> moved(static_cast<std::size_t>(vertices.rows()), 0);
  std::vector<SurfacePoint> near;
  if (closest_faces && closest_faces->size() == static_cast<std::size_t>(vertices.rows())) {
    near.resize(closest_faces->size());
    const auto n = static_cast<std::ptrdiff_t>(near.size());
#pragma omp parallel for schedule(static, 64)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      near[static_cast<std::size_t>(i)] = body.locate_near(vertices.row(i).transpose(), (*closest_faces)[static_cast<std::size_t>(i)]);
  } else {
    near = body.locate_all(vertices);
  }
  std::vector<Eigen::Index> stepped;  // the vertices the pass moved: only their closest points change
  for (int pass = 0; pass < max_passes; ++pass) {
    ++report.passes;
    stepped.clear();
    for (Eigen::Index i = 0; i < vertices.rows(); ++i) {
      const SurfacePoint& s = near[static_cast<std::size_t>(i)];
      // (A vertex a pass put on the level set may come back a rounding error short of it: left alone.)
      if (s.face < 0 || s.signed_distance >= margin - kRounding) continue;
      // Onto the level set s = margin along the gradient of s: exact while the
      // closest point stays on the same face, edge or vertex.
      const Eigen::Vector3d step = (margin - s.signed_distance) * s.normal;
      vertices.row(i) += step.transpose();
      moved[static_cast<std::size_t>(i)] = 1;
      stepped.push_back(i);
    }
    if (stepped.empty()) break;  // nothing moved: the last search still holds
    const auto count = static_cast<std::ptrdiff_t>(stepped.size());
#pragma omp parallel for schedule(static, 16)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const Eigen::Index i = stepped[static_cast<std::size_t>(k)];
      near[static_cast<std::size_t>(i)] = body.locate(vertices.row(i).transpose());
    }
  }
  if (closest_faces) {
    closest_faces->resize(near.size());
    for (std::size_t i = 0; i < near.size(); ++i) (*closest_faces)[i] = near[i].face;
  }
  if (vertices.rows() > 0) report.largest_move = (vertices - start).rowwise().norm().maxCoeff();
  for (std::size_t i = 0; i < near.size(); ++i) {
    report.moved += moved[i];
    report.still_within += near[i].face >= 0 && near[i].signed_distance < 0.5 * margin;
  }
  return report;
}

}  // namespace drape::geometry
