// grade_garment (garment_grading.hpp).
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>
#include <drape/garment_layers.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
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

// The length grade of a garment, as one map of heights for all its pieces
// (so that pieces never pass through each other for it: a shirt's hem over
// trousers' waist moves with it) and each piece's cloth. Above `legs_below`
// (the crotch of the mean body), heights grow by grade_length(g) below the
// garment's top, as they always have; a garment with a piece reaching below
// it (trousers, a dress) has the legs between crotch and floor (the mean
// body's soles) taken in evenly instead, the floor kept, and that piece's
// cloth keeps its lengths (an inseam does not grow with the waist). Graded
// about its top alone, MakeHuman's suit at grade 1.35 had its jeans' hems 16
// cm down, through the feet and the floor, and its start was refused.
struct LengthGrade {
  Eigen::VectorXd cloth;  // per vertex: its piece's length grade of the cloth
  double top = 0, length = 1, legs_below = 0, floor = 0;
  bool legs = false;  // some piece reaches below legs_below
  double height(double y) const {
    if (!legs || y >= legs_below) return top + length * (y - top);
    if (y <= floor) return y;
    const double at_crotch = top + length * (legs_below - top);
    return floor + (y - floor) * (at_crotch - floor) / (legs_below - floor);
  }
  // height(y) - y, as place_graded_garment has always added it above the legs.
  double shift(double y) const { return !legs || y >= legs_below ? (length - 1.0) * (y - top) : height(y) - y; }
};
LengthGrade length_grade(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, double g, double legs_below,
                         double floor) {
  const Eigen::Index n = x.rows();
  LengthGrade out;
  out.length = grade_length(g);
  out.top = n > 0 ? x.col(1).maxCoeff() : 0.0;
  out.cloth = Eigen::VectorXd::Constant(n, out.length);
  if (!std::isfinite(legs_below) || !std::isfinite(floor) || !(floor < legs_below) || n == 0) return out;
  const std::vector<int> piece = garment_pieces(faces, static_cast<int>(n));  // per face
  const int pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  std::vector<char> reaches_legs(static_cast<std::size_t>(pieces), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (x(faces(f, k), 1) < legs_below) reaches_legs[static_cast<std::size_t>(piece[static_cast<std::size_t>(f)])] = 1;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (reaches_legs[static_cast<std::size_t>(piece[static_cast<std::size_t>(f)])])
      for (int k = 0; k < 3; ++k) out.cloth(faces(f, k)) = 1.0, out.legs = true;
  out.legs_below = legs_below;
  out.floor = floor;
  return out;
}

// Grades the material space chart by chart (garment_grading.hpp): each
// chart's UVs about its centroid, which moves as under a uniform scale by g;
// along the rise by `length` of the chart's vertices (their piece's).
void grade_material_space(Mesh& mesh, double g, const Eigen::VectorXd& length) {
  int charts = 0;
  const std::vector<int> chart = uv_charts(mesh, &charts);
  // The 3D height of each UV index (of the first corner using it).
  Eigen::VectorXd height = Eigen::VectorXd::Constant(mesh.uv.rows(), std::nan(""));
  std::vector<double> chart_length(static_cast<std::size_t>(charts), 1.0);
  for (Eigen::Index f = 0; f < mesh.uv_faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      if (std::isnan(height(mesh.uv_faces(f, k)))) height(mesh.uv_faces(f, k)) = mesh.vertices(mesh.faces(f, k), 1);
      // (A chart lies in one piece: its faces are joined.)
      chart_length[static_cast<std::size_t>(chart[static_cast<std::size_t>(mesh.uv_faces(f, k))])] = length(mesh.faces(f, k));
    }
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
    const double l = chart_length[static_cast<std::size_t>(c)];
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
  if (grade != 1.0 && mesh.has_uv())
    grade_material_space(mesh, grade, Eigen::VectorXd::Constant(mesh.vertices.rows(), grade_length(grade)));
}

void grade_garment(Garment& garment, double grade, double legs_below, double floor) {
  if (!(grade >= kMinGrade && grade <= kMaxGrade))
    throw ConfigError("garment grade " + std::to_string(grade) + " is outside " + std::to_string(kMinGrade) + " to " +
                      std::to_string(kMaxGrade));
  if (grade == 1.0) return;
  garment.fit_grade *= grade;
  Eigen::MatrixX3d& x = garment.mesh.vertices;
  if (x.rows() == 0) return;
  const LengthGrade lengths = length_grade(x, garment.mesh.faces, grade, legs_below, floor);
  if (garment.mesh.has_uv()) grade_material_space(garment.mesh, grade, lengths.cloth);  // reads the ungraded heights
  const double cx = x.col(0).mean(), cz = x.col(2).mean();  // around the garment's centre line
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    x(v, 0) = cx + grade * (x(v, 0) - cx);
    x(v, 1) = lengths.height(x(v, 1));
    x(v, 2) = cz + grade * (x(v, 2) - cz);
  }
}

void place_graded_garment(Garment& garment, const Eigen::MatrixX3d& ungraded, const Eigen::MatrixX3d& mean_body,
                          const Eigen::MatrixX3d& fit_body, const Eigen::MatrixX3i& body_faces, double grade,
                          double legs_below, double floor) {
  if (ungraded.rows() != garment.mesh.vertices.rows() || mean_body.rows() != fit_body.rows())
    throw Error("place_graded_garment: the garment or the bodies do not match in size");
  if (ungraded.rows() == 0) return;
  const geometry::BodySurface mean(mean_body, body_faces);
  const std::vector<geometry::SurfacePoint> on_mean = mean.locate_all(ungraded);
  const LengthGrade lengths = length_grade(ungraded, garment.mesh.faces, grade, legs_below, floor);
  Eigen::MatrixX3d moved(ungraded.rows(), 3);
  for (Eigen::Index v = 0; v < ungraded.rows(); ++v) {
    const geometry::SurfacePoint& s = on_mean[static_cast<std::size_t>(v)];
    Eigen::Vector3d carried = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) carried += s.barycentric[k] * fit_body.row(body_faces(s.face, k)).transpose();
    Eigen::Vector3d p = carried + grade * (ungraded.row(v).transpose() - s.point);
    p.y() += lengths.shift(ungraded(v, 1));  // the length grade, as grade_garment's
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
