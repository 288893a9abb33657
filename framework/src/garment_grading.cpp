// grade_garment (garment_grading.hpp).
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace drape {
namespace {

// The UV chart of each UV index: UV indices joined by a face are one chart.
std::vector<int> uv_charts(const Mesh& mesh, int* count) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.uv.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (Eigen::Index f = 0; f < mesh.uv_faces.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[static_cast<std::size_t>(find(mesh.uv_faces(f, k)))] = find(mesh.uv_faces(f, 0));
  std::vector<int> chart(parent.size(), -1), id(parent.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < parent.size(); ++i) {
    const int root = find(static_cast<int>(i));
    if (id[static_cast<std::size_t>(root)] < 0) id[static_cast<std::size_t>(root)] = n++;
    chart[i] = id[static_cast<std::size_t>(root)];
  }
  *count = n;
  return chart;
}

// Grades the material space chart by chart (garment_grading.hpp): each
// chart's UVs about its centroid, which moves as under a uniform scale by g.
void grade_material_space(Mesh& mesh, double g, double l) {
  int charts = 0;
  const std::vector<int> chart = uv_charts(mesh, &charts);
  // The 3D height of each UV index (of the first corner using it).
  Eigen::VectorXd height = Eigen::VectorXd::Constant(mesh.uv.rows(), std::nan(""));
  for (Eigen::Index f = 0; f < mesh.uv_faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (std::isnan(height(mesh.uv_faces(f, k)))) height(mesh.uv_faces(f, k)) = mesh.vertices(mesh.faces(f, k), 1);
  for (int c = 0; c < charts; ++c) {
    // Least squares y = a . uv + b over the chart's UV indices.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    int n = 0;
    for (Eigen::Index i = 0; i < mesh.uv.rows(); ++i) {
      if (chart[static_cast<std::size_t>(i)] != c || std::isnan(height(i))) continue;
      const Eigen::Vector3d row(mesh.uv(i, 0), mesh.uv(i, 1), 1.0);
      normal += row * row.transpose();
      rhs += row * height(i);
      centroid += mesh.uv.row(i).transpose();
      ++n;
    }
    if (n == 0) continue;
    centroid /= n;
    const Eigen::Vector3d fit = normal.ldlt().solve(rhs);
    Eigen::Vector2d up(fit(0), fit(1));
    // Across the rise, a chart's cloth goes around the body (girth: g); along
    // it, its slope s mixes girth and length.
    Eigen::Matrix2d grade = g * Eigen::Matrix2d::Identity();
    const double s = std::min(up.norm(), 1.0);
    if (up.allFinite() && s > 1e-9) {
      up.normalize();
      const double along = std::sqrt(g * g * (1 - s * s) + l * l * s * s);
      grade += (along - g) * up * up.transpose();
    }
    for (Eigen::Index i = 0; i < mesh.uv.rows(); ++i)
      if (chart[static_cast<std::size_t>(i)] == c)
        mesh.uv.row(i) = (g * centroid + grade * (mesh.uv.row(i).transpose() - centroid)).transpose();
  }
}

}  // namespace

void grade_material(Mesh& mesh, double grade) {
  if (!(grade > 0.0) || !std::isfinite(grade)) throw ConfigError("material grade " + std::to_string(grade) + " is not > 0");
  if (grade != 1.0 && mesh.has_uv()) grade_material_space(mesh, grade, grade_length(grade));
}

void grade_garment(Garment& garment, double grade) {
  if (!(grade >= kMinGrade && grade <= kMaxGrade))
    throw ConfigError("garment grade " + std::to_string(grade) + " is outside " + std::to_string(kMinGrade) + " to " +
                      std::to_string(kMaxGrade));
  if (grade == 1.0) return;
  garment.fit_grade *= grade;
  Eigen::MatrixX3d& x = garment.mesh.vertices;
  if (x.rows() == 0) return;
  const double length = grade_length(grade);
  if (garment.mesh.has_uv()) grade_material_space(garment.mesh, grade, length);  // reads the ungraded heights
  const Eigen::RowVector3d top(x.col(0).mean(), x.col(1).maxCoeff(), x.col(2).mean());
  x = (x.rowwise() - top) * Eigen::Vector3d(grade, length, grade).asDiagonal();
  x.rowwise() += top;
}

void place_graded_garment(Garment& garment, const Eigen::MatrixX3d& ungraded, const Eigen::MatrixX3d& mean_body,
                          const Eigen::MatrixX3d& fit_body, const Eigen::MatrixX3i& body_faces, double grade) {
  if (ungraded.rows() != garment.mesh.vertices.rows() || mean_body.rows() != fit_body.rows())
    throw Error("place_graded_garment: the garment or the bodies do not match in size");
  if (ungraded.rows() == 0) return;
  const geometry::BodySurface mean(mean_body, body_faces);
  const std::vector<geometry::SurfacePoint> on_mean = mean.locate_all(ungraded);
  const double length = grade_length(grade), top = ungraded.col(1).maxCoeff();
  Eigen::MatrixX3d moved(ungraded.rows(), 3);
  for (Eigen::Index v = 0; v < ungraded.rows(); ++v) {
    const geometry::SurfacePoint& s = on_mean[static_cast<std::size_t>(v)];
    Eigen::Vector3d carried = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) carried += s.barycentric[k] * fit_body.row(body_faces(s.face, k)).transpose();
    Eigen::Vector3d p = carried + grade * (ungraded.row(v).transpose() - s.point);
    p.y() += (length - 1.0) * (ungraded(v, 1) - top);  // the length grade, as grade_garment's
    moved.row(v) = p.transpose() - ungraded.row(v);
  }
  // Neighbours nearest different parts of the body (an armpit's cloth, between
  // arm and torso) move apart: the displacements are smoothed over the
  // garment, so that the cloth there does not fold through itself. Dressing
  // then pushes out whatever the smoothing left inside.
  const auto neighbours = geometry::vertex_neighbours(garment.mesh.faces, static_cast<int>(ungraded.rows()));
  constexpr int kSmoothing = 10;
  for (int it = 0; it < kSmoothing; ++it) {
    Eigen::MatrixX3d next = moved;
    for (Eigen::Index v = 0; v < moved.rows(); ++v) {
      const auto& nb = neighbours[static_cast<std::size_t>(v)];
      if (nb.empty()) continue;
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      for (int w : nb) mean += moved.row(w);
      next.row(v) = 0.5 * moved.row(v) + 0.5 * mean / static_cast<double>(nb.size());
    }
    moved.swap(next);
  }
  garment.mesh.vertices = ungraded + moved;
}

}  // namespace drape
