#include <drape/garment_layers.hpp>

#include <drape/geometry/nearest_triangles.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

namespace drape {
namespace {

Eigen::MatrixX3i faces_of(const Eigen::MatrixX3i& faces, const std::vector<int>& piece, int p) {
  std::vector<int> rows;
  for (int f = 0; f < faces.rows(); ++f)
    if (piece[static_cast<std::size_t>(f)] == p) rows.push_back(f);
  Eigen::MatrixX3i out(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = faces.row(rows[i]);
  return out;
}

std::vector<int> vertices_of(const Eigen::MatrixX3i& faces) {
  std::vector<int> v(faces.data(), faces.data() + faces.size());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The closest point of the inner faces to p within `reach` (face -1: none);
// NearestTriangles is the BVH closest-point query without the inside sign.
geometry::SurfacePoint within(const geometry::NearestTriangles& faces, const Eigen::Vector3d& p, double reach) {
  geometry::SurfacePoint hit = faces.nearest(p);
  if (!(hit.signed_distance <= reach)) hit.face = -1;
  return hit;
}

// The mean signed body distance of the vertices of `piece` within `reach` of
// `other` (NaN when none is): the closer piece where two overlap is inside.
double overlap_depth(const std::vector<int>& piece, const Eigen::MatrixX3i& other, const Eigen::MatrixX3d& x,
                     const BodyQuery& body, double reach) {
  double sum = 0;
  int n = 0;
  const geometry::NearestTriangles near(x, other);
  for (int v : piece)
    if (within(near, x.row(v).transpose(), reach).face >= 0) sum += body.closest(x.row(v).transpose()).signed_distance, ++n;
  return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

// Moves the vertices of `outer` out of `inner` (see the header); returns the vertices moved.
std::set<int> lay_outside(Eigen::MatrixX3d& x, const Eigen::MatrixX3i& outer, const Eigen::MatrixX3i& inner,
                          const BodyQuery& body, const LayerOptions& o) {
  std::vector<std::vector<int>> nb(static_cast<std::size_t>(x.rows()));
  for (int f = 0; f < outer.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = outer(f, e), b = outer(f, (e + 1) % 3);
      nb[static_cast<std::size_t>(a)].push_back(b);
      nb[static_cast<std::size_t>(b)].push_back(a);
    }
  const std::vector<int> own = vertices_of(outer);
  std::set<int> moved;
  const geometry::NearestTriangles near(x, inner);  // built once: the inner piece does not move
  for (int round = 0; round < o.rounds; ++round) {
    Eigen::MatrixX3d move = Eigen::MatrixX3d::Zero(x.rows(), 3);
    bool any = false;
    for (int v : own) {
      const Eigen::Vector3d p = x.row(v).transpose();
      const geometry::SurfacePoint n = within(near, p, o.reach);
      if (n.face < 0) continue;
      const Eigen::Vector3d a = x.row(inner(n.face, 0)), b = x.row(inner(n.face, 1)), c = x.row(inner(n.face, 2));
      Eigen::Vector3d normal = (b - a).cross(c - a);
      if (!(normal.norm() > 0)) continue;
      normal.normalize();
      // Outward: as the body's surface faces under the inner piece.
      if (normal.dot(body.closest(n.point).normal) < 0) normal = -normal;
      const double outside = (p - n.point).dot(normal);
      if (outside < o.margin) move.row(v) = ((o.margin - outside) * normal).transpose(), moved.insert(v), any = true;
    }
    if (!any) break;
    // Spread: a vertex takes its neighbours' mean move where that is larger
    // than its own, so a hem lifts as a band instead of a row of spikes.
    for (int s = 0; s < o.smoothing_steps; ++s) {
      Eigen::MatrixX3d spread = move;
      for (int v : own) {
        const auto& around = nb[static_cast<std::size_t>(v)];
        if (around.empty()) continue;
        Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
        for (int w : around) mean += move.row(w);
        mean /= static_cast<double>(around.size());
        if (mean.norm() > move.row(v).norm()) spread.row(v) = mean;
      }
      move.swap(spread);
    }
    x += move;
  }
  return moved;
}

}  // namespace

std::vector<int> garment_pieces(const Eigen::MatrixX3i& faces, int vertex_count) {
  std::vector<int> parent(static_cast<std::size_t>(vertex_count));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = find(faces(f, 0)), b = find(faces(f, k));
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> label(static_cast<std::size_t>(vertex_count), -1), piece(static_cast<std::size_t>(faces.rows()));
  int next = 0;
  for (int f = 0; f < faces.rows(); ++f) {
    int& l = label[static_cast<std::size_t>(find(faces(f, 0)))];
    if (l < 0) l = next++;
    piece[static_cast<std::size_t>(f)] = l;
  }
  return piece;
}

LayerReport separate_layers(Garment& garment, const BodyQuery& body, const LayerOptions& options) {
  LayerReport report;
  Eigen::MatrixX3d& x = garment.mesh.vertices;
  const Eigen::MatrixX3i& faces = garment.mesh.faces;
  const std::vector<int> piece = garment_pieces(faces, static_cast<int>(x.rows()));
  report.pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  if (report.pieces < 2) return report;
  std::vector<Eigen::MatrixX3i> part(static_cast<std::size_t>(report.pieces));
  std::vector<std::vector<int>> verts(part.size());
  for (int p = 0; p < report.pieces; ++p) {
    part[static_cast<std::size_t>(p)] = faces_of(faces, piece, p);
    verts[static_cast<std::size_t>(p)] = vertices_of(part[static_cast<std::size_t>(p)]);
  }
  std::set<int> moved;
  for (int a = 0; a < report.pieces; ++a)
    for (int b = a + 1; b < report.pieces; ++b) {
      const std::size_t i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
      const double da = overlap_depth(verts[i], part[j], x, body, options.reach);
      const double db = overlap_depth(verts[j], part[i], x, body, options.reach);
      if (std::isnan(da) || std::isnan(db)) continue;  // apart: no layers to lay
      const bool a_inside = da <= db;
      const std::set<int> m = lay_outside(x, a_inside ? part[j] : part[i], a_inside ? part[i] : part[j], body, options);
      moved.insert(m.begin(), m.end());
      report.crossings += geometry::surface_crossings(x, part[i], x, part[j]).total();
    }
  report.moved = static_cast<int>(moved.size());
  return report;
}

}  // namespace drape
