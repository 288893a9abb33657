#pragma once
// Closest points on a triangle mesh when the inside/outside sign is not
// needed: the bounding-volume hierarchy of BodySurface alone, refitted to new
// vertex positions without recomputing any normals (BodySurface::update spends
// most of its time on the angle-weighted pseudo-normals), and queries that
// start from a hint face.
//
// The training losses query the prediction's closest body points at every
// step; the hint is the face found for the same garment vertex of the ground
// truth, usually the answer or next to it, so the search opens only the few
// boxes closer than that face.
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/nearby_faces.hpp>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace drape::geometry {

class NearestTriangles {
 public:
  // Throws Error naming the face when an index is out of range, or when there are no faces.
  NearestTriangles(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);
  ~NearestTriangles();
  NearestTriangles(NearestTriangles&&) noexcept;
  NearestTriangles& operator=(NearestTriangles&&) noexcept;

  // Same faces, new positions: the boxes are refitted in O(V + F).
  void update(const Eigen::MatrixX3d& vertices);

  // The closest surface point of p: face, barycentric, point and feature as
  // BodySurface::locate finds them; signed_distance is the unsigned distance
  // and normal is zero (no sign without pseudo-normals). hint: a face expected
  // near p, or -1. The point is the same with or without a hint; between
  // faces at the same distance the lowest-numbered wins, whatever the hint.
  SurfacePoint nearest(const Eigen::Vector3d& p, int hint = -1) const;

  // One query per row of `points`; hints (one per row, -1 for none) may be empty.
  std::vector<SurfacePoint> nearest_all(const Eigen::MatrixX3d& points, const std::vector<int>& hints = {}) const;

  // For each row y_i of `points` with its closest point hits[i] on this mesh,
  // the faces within dist(y_i, hits[i]) + slack of y_i, nearest first, at most
  // max_faces of them (the list is then complete up to the first left out).
  NearbyFaces nearby(const Eigen::MatrixX3d& points, const std::vector<SurfacePoint>& hits, double slack,
                     int max_faces) const;

  // nearest(x), found from the faces listed near row i of the points the list
  // was made for (y, the same double values): the same point, face and
  // feature bits as nearest(x) whatever x, the tree searched only when the
  // list cannot prove the answer (x too far from y).
  SurfacePoint nearest_from(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const NearbyFaces& near, int i) const;

  const Eigen::MatrixX3i& faces() const { return faces_; }

 private:
  Eigen::MatrixX3i faces_;
  Eigen::Index num_vertices_ = 0;
  std::unique_ptr<TriangleBvh> bvh_;
};

}  // namespace drape::geometry
