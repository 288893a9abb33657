#pragma once
// Closest points on triangles and on a closed body surface, with a sign that
// says inside or outside.
//
// The sign uses angle-weighted pseudo-normals (Baerentzen & Aanaes, "Signed
// distance computation using the angle weighted pseudonormal", 2005): the
// closest point lies on a face, an edge or a vertex, and the sign of
// (p - closest) . n with n the face normal, the sum of the two face normals at
// the edge, or the angle-weighted sum of the face normals at the vertex is
// exact on a closed, consistently oriented 2-manifold. Plain face normals get
// it wrong near edges and vertices (both faces of a sharp edge "see" the point).
//
// Acceleration: a bounding-volume hierarchy over the triangles whose boxes are
// refitted (not rebuilt) when the body moves; `drape bench geometry` measures it
// against CGAL's AABB tree, a nanoflann kd-tree over vertices and a uniform grid.
#include <drape/energy.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

namespace drape::geometry {

// Closest-point searches are shared among threads only from this many on. A
// coarse shirt's thousand searches take about half a millisecond: on an idle
// 2-core machine `drape predict --pose` took the same 28 ms with one thread
// or two, and with the other core busy (a generation beside it) 57-63 ms
// with one against 164-174 ms with two, the loops' barriers waiting for a
// thread the busy core had not yet run. Used by the push-out and by
// BodySurface's batch queries.
constexpr std::ptrdiff_t kParallelSearches = 8192;

// The part of triangle (a, b, c) a closest point lies on.
enum class TriangleFeature : std::uint8_t { vertex_a, vertex_b, vertex_c, edge_ab, edge_bc, edge_ca, interior };

struct TrianglePoint {
  Eigen::Vector3d point;
  Eigen::Vector3d barycentric;  // weights of a, b, c: each in [0, 1], sum 1
  TriangleFeature feature;
};

// The exact closest point of the closed triangle to p (Ericson, Real-Time
// Collision Detection, 5.1.5: Voronoi regions by sign tests, in double).
// Degenerate triangles (collinear or coincident corners) are handled: the
// answer is then the closest point of their segments, always finite.
TrianglePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const Eigen::Vector3d& c);

// Where a query point meets a mesh surface.
struct SurfacePoint {
  int face = -1;                                            // -1: nothing within the search radius
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();    // weights of the face's corners
  Eigen::Vector3d point = Eigen::Vector3d::Zero();          // the closest surface point
  // Unit outward normal: the gradient of the signed distance, (p - point) / signed_distance;
  // the pseudo-normal of the feature when p lies on the surface (distance ~ 0).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double signed_distance = 0;                               // < 0 inside
  TriangleFeature feature = TriangleFeature::interior;
};

class TriangleBvh;  // internal acceleration structure
class PseudoNormals;  // pseudo_normals.hpp

// A body surface for closest-point queries. The sign is meaningful for a
// closed, consistently oriented (counter-clockwise seen from outside) manifold;
// on other meshes distances and closest points are still exact.
// Queries are const and thread-safe; update() is not concurrent with queries.
class BodySurface final : public BodyQuery {
 public:
  // Throws Error naming the face when an index is out of range, or when there are no faces.
  BodySurface(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);
  explicit BodySurface(const Mesh& mesh);
  ~BodySurface() override;
  BodySurface(BodySurface&&) noexcept;
  BodySurface& operator=(BodySurface&&) noexcept;

  Hit closest(const Eigen::Vector3d& p) const override;

  // The closest surface point; with max_distance, face = -1 when the surface is farther.
  SurfacePoint locate(const Eigen::Vector3d& p, double max_distance = std::numeric_limits<double>::infinity()) const;
  // The same closest point, the search started from a face expected near p
  // (its distance bounds the search; the answer is locate()'s: of faces at the
  // same distance the lowest-numbered wins, with or without a hint).
  SurfacePoint locate_near(const Eigen::Vector3d& p, int hint) const;
  // The same within max_distance (face = -1 when the surface is farther):
  // a far point's search is cut short, and a nearer one's answer is unchanged.
  SurfacePoint locate_near(const Eigen::Vector3d& p, int hint, double max_distance) const;
  // The closest point on the faces not labelled `excluded` (face_labels: one
  // label per face), signed like locate()'s: by the face normal, or the whole
  // surface's pseudo-normal at an edge or vertex. (Near the label's border that
  // is the side of the far patch's surface, not inside/outside the body.)
  SurfacePoint locate_excluding(const Eigen::Vector3d& p, const std::vector<int>& face_labels, int excluded,
                                double max_distance = std::numeric_limits<double>::infinity()) const;
  // The faces the closed segment (p, q) passes through or touches
  // (segment_pierces_triangle, exact), appended to `out` in no set order.
  void faces_crossed(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::vector<int>& out) const;
  // One query per row of `points`, in parallel (OpenMP).
  std::vector<SurfacePoint> locate_all(const Eigen::MatrixX3d& points, double max_distance = std::numeric_limits<double>::infinity()) const;
  Eigen::VectorXd signed_distances(const Eigen::MatrixX3d& points) const;

  // What update() recomputes besides the hierarchy's boxes. all: every
  // normal, for the accessors below. on_demand: none; each query computes
  // the pseudo-normal of the feature its closest point lies on
  // (PseudoNormals, the same bits). A push-out of a thousand garment
  // vertices needs a few thousand of a body's normals; all of them, with
  // three angles per face, cost more than the queries.
  enum class Normals { all, on_demand };
  // New vertex positions for the same faces (a morphing or moving body): the
  // normals recomputed (or left to the queries) and the hierarchy's boxes
  // refitted in O(V + F). Query speed degrades only if the body deforms far
  // from the shape it was built on; then rebuild() restores it. Throws Error
  // on a wrong vertex count.
  void update(const Eigen::MatrixX3d& vertices, Normals normals = Normals::all);
  void rebuild();
  // Counts update() calls: a caller that keeps answers for some points knows
  // they still hold while the revision is the same.
  std::uint64_t revision() const { return revision_; }

  const Eigen::MatrixX3d& vertices() const { return vertices_; }
  const Eigen::MatrixX3i& faces() const { return faces_; }
  // The vertices next to each vertex (the faces' edges), made at the first
  // call: the faces never change.
  const VertexAdjacency& vertex_adjacency() const;
  // Unit angle-weighted pseudo-normals of the vertices (outward on a closed
  // mesh). Throws Error after an update() that left normals to the queries.
  const Eigen::MatrixX3d& vertex_normals() const;
  // Unit face normals (zero for a degenerate face), current with update();
  // the same Error as vertex_normals().
  const Eigen::MatrixX3d& face_normals() const;
  // The face across each edge of each face (geometry::face_neighbours).
  const std::vector<std::array<int, 3>>& face_neighbours() const { return face_neighbours_; }

 private:
  void compute_normals();
  SurfacePoint finish(const Eigen::Vector3d& p, int face, const TrianglePoint& hit) const;
  // locate and locate_excluding: face_labels null for every face.
  SurfacePoint search(const Eigen::Vector3d& p, double max_distance, const int* face_labels, int excluded,
                      int hint = -1) const;

  Eigen::MatrixX3d vertices_;
  Eigen::MatrixX3i faces_;
  Eigen::MatrixX3d face_normals_;    // unit (zero for degenerate faces)
  Eigen::MatrixX3d vertex_normals_;  // unit angle-weighted pseudo-normals
  Eigen::MatrixX3d edge_normals_;    // [3F] per face edge (ab, bc, ca): sum of its faces' normals, unit
  std::vector<std::array<int, 3>> face_neighbours_;  // the face across each edge (ab, bc, ca), -1 on a boundary
  double on_surface_tolerance_ = 0;  // below this distance the normal is the pseudo-normal
  std::uint64_t revision_ = 0;
  std::unique_ptr<TriangleBvh> bvh_;
  // Set by update(..., Normals::on_demand): the normals above are stale and
  // each query's pseudo-normal comes from here.
  std::unique_ptr<PseudoNormals> on_demand_;
  bool normals_current_ = true;
  mutable std::unique_ptr<std::once_flag> adjacency_once_ = std::make_unique<std::once_flag>();
  mutable std::unique_ptr<VertexAdjacency> adjacency_;
};

}  // namespace drape::geometry
