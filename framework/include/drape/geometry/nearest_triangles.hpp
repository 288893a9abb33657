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

  const Eigen::MatrixX3i& faces() const { return faces_; }

 private:
  Eigen::MatrixX3i faces_;
  Eigen::Index num_vertices_ = 0;
  std::unique_ptr<TriangleBvh> bvh_;
};

}  // namespace drape::geometry
