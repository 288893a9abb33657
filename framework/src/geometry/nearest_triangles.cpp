#include <drape/geometry/nearest_triangles.hpp>

#include "triangle_bvh.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace drape::geometry {

NearestTriangles::NearestTriangles(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces)
    : faces_(faces), num_vertices_(vertices.rows()) {
  if (faces.rows() == 0) throw Error("nearest triangles: the mesh has no faces");
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= vertices.rows())
        throw Error("nearest triangles: face " + std::to_string(f) + " uses vertex " + std::to_string(faces(f, k)) +
                    ", outside [0, " + std::to_string(vertices.rows()) + ")");
  bvh_ = std::make_unique<TriangleBvh>(vertices, faces_);
}

NearestTriangles::~NearestTriangles() = default;
NearestTriangles::NearestTriangles(NearestTriangles&&) noexcept = default;
NearestTriangles& NearestTriangles::operator=(NearestTriangles&&) noexcept = default;

void NearestTriangles::update(const Eigen::MatrixX3d& vertices) {
  if (vertices.rows() != num_vertices_)
    throw Error("nearest triangles update: " + std::to_string(vertices.rows()) + " vertices given, the mesh has " +
                std::to_string(num_vertices_));
  bvh_->refit(vertices);
}

namespace {

SurfacePoint surface_point(const Eigen::Vector3d& p, int face, const TrianglePoint& hit) {
  SurfacePoint r;
  r.face = face;
  r.barycentric = hit.barycentric;
  r.point = hit.point;
  r.feature = hit.feature;
  r.signed_distance = (p - hit.point).norm();
  return r;
}

// v as a float no larger than v: a list's distances and radii may only err
// towards opening more faces.
float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

// More than the rounding of every distance compared below (~1e-15 m on a body
// of a few metres): a face is passed over only when it is farther by this.
constexpr double kProofMargin = 1e-9;

}  // namespace

SurfacePoint NearestTriangles::nearest(const Eigen::Vector3d& p, int hint) const {
  TrianglePoint hit;
  const int face = bvh_->nearest(p, std::numeric_limits<double>::infinity(), hit, nullptr, 0, hint);
  if (face < 0) return {};  // only for a non-finite p
  return surface_point(p, face, hit);
}

NearbyFaces NearestTriangles::nearby(const Eigen::MatrixX3d& points, const std::vector<SurfacePoint>& hits,
                                     double slack, int max_faces) const {
  if (static_cast<Eigen::Index>(hits.size()) != points.rows())
    throw Error("nearest triangles: " + std::to_string(hits.size()) + " closest points for " +
                std::to_string(points.rows()) + " points");
  if (!(slack >= 0) || max_faces < 1) throw Error("nearest triangles: nearby lists need slack >= 0 and max_faces >= 1");
  NearbyFaces near;
  near.start.reserve(static_cast<std::size_t>(points.rows()) + 1);
  near.start.push_back(0);
  near.complete.reserve(static_cast<std::size_t>(points.rows()));
  std::vector<std::pair<double, int>> found;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d y = points.row(i).transpose();
    double radius = 0.0;  // an empty, complete-to-nothing list for a point without a closest point
    if (hits[static_cast<std::size_t>(i)].face >= 0 && y.allFinite()) {
      const double own = (y - hits[static_cast<std::size_t>(i)].point).squaredNorm();
      radius = std::sqrt(own) + slack;
      // (At least `own`: the point's own face is listed whatever the rounding of the root.)
      bvh_->within(y, std::max(radius * radius, own), found);
    } else {
      found.clear();
    }
    std::sort(found.begin(), found.end());
    const std::size_t kept = std::min(found.size(), static_cast<std::size_t>(max_faces));
    for (std::size_t k = 0; k < kept; ++k) {
      near.face.push_back(found[k].second);
      near.reach.push_back(round_down(std::sqrt(found[k].first)));
    }
    near.complete.push_back(round_down(kept < found.size() ? std::sqrt(found[kept].first) : radius));
    near.start.push_back(static_cast<int>(near.face.size()));
  }
  return near;
}

SurfacePoint NearestTriangles::nearest_from(const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                                            const NearbyFaces& near, int i) const {
  if (i < 0 || i >= near.points()) throw Error("nearest triangles: no nearby list " + std::to_string(i));
  if (!x.allFinite()) return {};
  const double moved = (x - y).norm();

  double best = std::numeric_limits<double>::infinity();  // squared, as the tree compares
  int best_face = -1;
  TrianglePoint hit;
  const int begin = near.start[static_cast<std::size_t>(i)], end = near.start[static_cast<std::size_t>(i) + 1];
  // x's best distance is about y's (reach[begin]); the list proves it only if
  // it is complete beyond that plus how far x moved. When it is not, testing
  // its faces first would be wasted: straight to the tree.
  if (begin == end || double(near.complete[static_cast<std::size_t>(i)]) - moved <= double(near.reach[static_cast<std::size_t>(begin)]))
    return nearest(x, begin == end ? -1 : near.face[static_cast<std::size_t>(begin)]);
  for (int k = begin; k < end; ++k) {
    // Listed nearest first: from here on no face can come within `best`.
    if (double(near.reach[static_cast<std::size_t>(k)]) - moved > std::sqrt(best) + kProofMargin)
      return surface_point(x, best_face, hit);
    const int f = near.face[static_cast<std::size_t>(k)];
    const TrianglePoint q = bvh_->face_point(x, f);
    const double d2 = (q.point - x).squaredNorm();
    // The tree's rule: of faces at the same computed distance the lowest-numbered wins.
    if (d2 < best || (d2 == best && f < best_face)) best = d2, best_face = f, hit = q;
  }
  if (best_face >= 0 && double(near.complete[static_cast<std::size_t>(i)]) - moved > std::sqrt(best) + kProofMargin)
    return surface_point(x, best_face, hit);
  return nearest(x, best_face);
}

std::vector<SurfacePoint> NearestTriangles::nearest_all(const Eigen::MatrixX3d& points, const std::vector<int>& hints) const {
  if (!hints.empty() && static_cast<Eigen::Index>(hints.size()) != points.rows())
    throw Error("nearest triangles: " + std::to_string(hints.size()) + " hints for " + std::to_string(points.rows()) +
                " points");
  std::vector<SurfacePoint> out(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out[i] = nearest(points.row(i).transpose(), hints.empty() ? -1 : hints[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace drape::geometry
