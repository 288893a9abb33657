#include <drape/geometry/closest_point.hpp>

#include "triangle_bvh.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/pseudo_normals.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace drape::geometry {
namespace {

void check_faces(const Eigen::MatrixX3i& faces, int num_vertices) {
  if (faces.rows() == 0) throw Error("body surface: the mesh has no faces");
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= num_vertices)
        throw Error("body surface: face " + std::to_string(f) + " uses vertex " + std::to_string(faces(f, k)) +
                    ", outside [0, " + std::to_string(num_vertices) + ")");
}

}  // namespace

BodySurface::BodySurface(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces)
    : vertices_(vertices), faces_(faces) {
  check_faces(faces_, static_cast<int>(vertices_.rows()));
  if (!vertices_.allFinite()) throw Error("body surface: the vertices are not all finite");
  face_neighbours_ = geometry::face_neighbours(faces_);
  compute_normals();
  bvh_ = std::make_unique<TriangleBvh>(vertices_, faces_);
}

BodySurface::BodySurface(const Mesh& mesh) : BodySurface(mesh.vertices, mesh.faces) {}

const VertexAdjacency& BodySurface::vertex_adjacency() const {
  std::call_once(*adjacency_once_, [this] {
    adjacency_ = std::make_unique<VertexAdjacency>(geometry::vertex_adjacency(edge_list(faces_), static_cast<int>(vertices_.rows())));
  });
  return *adjacency_;
}
BodySurface::~BodySurface() = default;
BodySurface::BodySurface(BodySurface&&) noexcept = default;
BodySurface& BodySurface::operator=(BodySurface&&) noexcept = default;

void BodySurface::compute_normals() {
  // The pseudo-normals' pieces (pseudo_normals.hpp), for every face at once.
  const int nf = static_cast<int>(faces_.rows());
  face_normals_.resize(nf, 3);
  vertex_normals_ = Eigen::MatrixX3d::Zero(vertices_.rows(), 3);
  for (int f = 0; f < nf; ++f) {
    face_normals_.row(f) = face_normal(vertices_, faces_, f);
    for (int k = 0; k < 3; ++k) vertex_normals_.row(faces_(f, k)) += corner_angle(vertices_, faces_, f, k) * face_normals_.row(f);
  }
  vertex_normals_.rowwise().normalize();
  edge_normals_.resize(3 * static_cast<Eigen::Index>(nf), 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      // Non-manifold edges have no single mate: their pseudo-normal is the face's own.
      const int g = face_neighbours_[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
      Eigen::Vector3d n = face_normals_.row(f);
      if (g >= 0) n += face_normals_.row(g).transpose();
      edge_normals_.row(3 * f + k) = n.normalized();
    }
  on_surface_tolerance_ = on_surface_tolerance(vertices_);
}

void BodySurface::update(const Eigen::MatrixX3d& vertices, Normals normals) {
  if (vertices.rows() != vertices_.rows())
    throw Error("body surface update: " + std::to_string(vertices.rows()) + " vertices given, the body has " +
                std::to_string(vertices_.rows()));
  if (!vertices.allFinite()) throw Error("body surface update: the vertices are not all finite");
  vertices_ = vertices;
  if (normals == Normals::all) {
    compute_normals();
    normals_current_ = true;
  } else {
    if (!on_demand_) on_demand_ = std::make_unique<PseudoNormals>(faces_);
    on_surface_tolerance_ = on_surface_tolerance(vertices_);
    normals_current_ = false;
  }
  bvh_->refit(vertices_);
  ++revision_;
}

const Eigen::MatrixX3d& BodySurface::vertex_normals() const {
  if (!normals_current_) throw Error("body surface: the vertex normals were left to the queries (update with Normals::all)");
  return vertex_normals_;
}

const Eigen::MatrixX3d& BodySurface::face_normals() const {
  if (!normals_current_) throw Error("body surface: the face normals were left to the queries (update with Normals::all)");
  return face_normals_;
}

void BodySurface::rebuild() { bvh_ = std::make_unique<TriangleBvh>(vertices_, faces_); }

SurfacePoint BodySurface::finish(const Eigen::Vector3d& p, int face, const TrianglePoint& hit) const {
  using F = TriangleFeature;
  if (!normals_current_)
    return signed_surface_point(p, face, hit, on_demand_->at(vertices_, face, hit.feature), on_surface_tolerance_);
  Eigen::Vector3d pseudo;
  switch (hit.feature) {
    case F::vertex_a: pseudo = vertex_normals_.row(faces_(face, 0)); break;
    case F::vertex_b: pseudo = vertex_normals_.row(faces_(face, 1)); break;
    case F::vertex_c: pseudo = vertex_normals_.row(faces_(face, 2)); break;
    case F::edge_ab: pseudo = edge_normals_.row(3 * face + 0); break;
    case F::edge_bc: pseudo = edge_normals_.row(3 * face + 1); break;
    case F::edge_ca: pseudo = edge_normals_.row(3 * face + 2); break;
    default: pseudo = face_normals_.row(face); break;
  }
  return signed_surface_point(p, face, hit, pseudo, on_surface_tolerance_);
}

SurfacePoint BodySurface::search(const Eigen::Vector3d& p, double max_distance, const int* face_labels,
                                 int excluded, int hint) const {
  TrianglePoint hit;
  const double bound = std::isinf(max_distance) ? max_distance : max_distance * max_distance;
  const int face = bvh_->nearest(p, bound, hit, face_labels, excluded, hint);
  if (face < 0) return {};
  return finish(p, face, hit);
}

SurfacePoint BodySurface::locate(const Eigen::Vector3d& p, double max_distance) const {
  return search(p, max_distance, nullptr, 0);
}

void BodySurface::faces_crossed(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::vector<int>& out) const {
  const std::size_t first = out.size();
  bvh_->along_segment(p, q, out);
  std::size_t kept = first;
  for (std::size_t i = first; i < out.size(); ++i) {
    const int f = out[i];
    if (segment_pierces_triangle(p, q, vertices_.row(faces_(f, 0)), vertices_.row(faces_(f, 1)), vertices_.row(faces_(f, 2))))
      out[kept++] = f;
  }
  out.resize(kept);
}

SurfacePoint BodySurface::locate_near(const Eigen::Vector3d& p, int hint) const {
  return locate_near(p, hint, std::numeric_limits<double>::infinity());
}

SurfacePoint BodySurface::locate_near(const Eigen::Vector3d& p, int hint, double max_distance) const {
  return search(p, max_distance, nullptr, 0, hint < faces_.rows() ? hint : -1);
}

SurfacePoint BodySurface::locate_excluding(const Eigen::Vector3d& p, const std::vector<int>& face_labels, int excluded,
                                           double max_distance) const {
  if (face_labels.size() != static_cast<std::size_t>(faces_.rows()))
    throw Error("body surface: " + std::to_string(face_labels.size()) + " face labels given, the body has " +
                std::to_string(faces_.rows()) + " faces");
  return search(p, max_distance, face_labels.data(), excluded);
}

std::vector<SurfacePoint> BodySurface::locate_all(const Eigen::MatrixX3d& points, double max_distance) const {
  std::vector<SurfacePoint> out(points.rows());
  const Eigen::Index n = points.rows();
#pragma omp parallel for schedule(static, 64) if (n >= kParallelSearches)
  for (Eigen::Index i = 0; i < n; ++i) out[i] = locate(points.row(i).transpose(), max_distance);
  return out;
}

Eigen::VectorXd BodySurface::signed_distances(const Eigen::MatrixX3d& points) const {
  Eigen::VectorXd d(points.rows());
  const Eigen::Index n = points.rows();
#pragma omp parallel for schedule(static, 64) if (n >= kParallelSearches)
  for (Eigen::Index i = 0; i < n; ++i) d[i] = locate(points.row(i).transpose()).signed_distance;
  return d;
}

BodyQuery::Hit BodySurface::closest(const Eigen::Vector3d& p) const {
  const SurfacePoint s = locate(p);
  return {s.point, s.normal, s.signed_distance};
}

}  // namespace drape::geometry
