#include <drape/geometry/girth.hpp>

#include <drape/geometry/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace drape::geometry {
namespace {

// Andrew's monotone chain; the hull's perimeter.
double hull_perimeter(std::vector<Eigen::Vector2d> p) {
  if (p.size() < 3) return 0.0;
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (const auto& q : p) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], q) <= 0) --k;
    hull[k++] = q;
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  double perimeter = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) perimeter += (hull[(i + 1) % hull.size()] - hull[i]).norm();
  return perimeter;
}

}  // namespace

Girth horizontal_girth(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, double height,
                       const Eigen::Vector2d& centre, const Eigen::MatrixX2d* uv, const Eigen::MatrixX3i* uv_faces) {
  const bool material = uv && uv_faces && uv_faces->rows() == faces.rows();
  // Off every vertex: a vertex exactly on the plane would cut its faces at a
  // corner, and the segments would not chain.
  for (bool moved = true; moved;) {
    moved = false;
    for (Eigen::Index v = 0; v < vertices.rows(); ++v)
      if (vertices(v, 1) == height) {
        height += 1e-9;
        moved = true;
        break;
      }
  }
  // Each cut face gives one segment between two cut edges; an edge is named
  // by its sorted vertex pair, so that neighbouring faces share the point.
  using Edge = std::pair<int, int>;
  std::map<Edge, Eigen::Vector2d> point;
  std::map<Edge, std::vector<Edge>> next;
  // Per face's segment (its two cut edges, in order): its length in the
  // material space, each end mapped by the face's own corners (material
  // coordinates may jump across a seam, so the ends are not shared).
  std::map<std::pair<Edge, Edge>, double> material_step;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    Edge cut[3];
    Eigen::Vector2d cut_uv[3];
    int cuts = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      const double ya = vertices(a, 1) - height, yb = vertices(b, 1) - height;
      if ((ya < 0) == (yb < 0)) continue;
      const Edge e{std::min(a, b), std::max(a, b)};
      const double t = ya / (ya - yb);
      const Eigen::Vector3d p = vertices.row(a) + t * (vertices.row(b) - vertices.row(a));
      point.emplace(e, Eigen::Vector2d(p.x(), p.z()));
      if (material && cuts < 3) {
        const Eigen::Vector2d ua = uv->row((*uv_faces)(f, k)), ub = uv->row((*uv_faces)(f, (k + 1) % 3));
        cut_uv[cuts] = ua + t * (ub - ua);
      }
      cut[cuts++] = e;
    }
    if (cuts != 2) continue;
    if (material) {
      const double step = (cut_uv[1] - cut_uv[0]).norm();
      material_step[{cut[0], cut[1]}] = step;
      material_step[{cut[1], cut[0]}] = step;
    }
    next[cut[0]].push_back(cut[1]);
    next[cut[1]].push_back(cut[0]);
  }
  Girth out;
  std::map<Edge, bool> visited;
  for (const auto& [start, unused] : next) {
    if (visited[start]) continue;
    // Walk the chain; a loop closes when it comes back to its start.
    Polygon2 loop;
    Edge current = start;
    bool closed = false;
    double material_length = 0.0;
    const auto material_of = [&](const Edge& a, const Edge& b) {
      const auto it = material_step.find({a, b});
      return it == material_step.end() ? 0.0 : it->second;
    };
    while (!visited[current]) {
      visited[current] = true;
      loop.push_back(point.at(current));
      const auto& n = next.at(current);
      Edge step{-1, -1};
      for (const Edge& e : n)
        if (!visited[e]) step = e;  // the way back is visited already
      if (step.first < 0) {
        closed = std::find(n.begin(), n.end(), start) != n.end() && loop.size() > 2;
        if (closed) material_length += material_of(current, start);
        break;
      }
      material_length += material_of(current, step);
      current = step;
    }
    if (!closed) continue;
    ++out.loops;
    Polygon2 ring = loop;
    ring.push_back(loop.front());
    const double length = polyline_length(ring);
    out.longest_loop = std::max(out.longest_loop, length);
    if (!point_in_polygon(loop, centre)) continue;
    if (out.found && length <= out.length) continue;  // of nested loops, the outer one
    out.found = true;
    out.length = length;
    out.tape = hull_perimeter(loop);
    out.material_length = material ? material_length : 0.0;
  }
  return out;
}

double crotch_height(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces) {
  const double y0 = body.col(1).minCoeff(), h = body.col(1).maxCoeff() - y0;
  // The centre line in depth: midway between the front and the back of the
  // trunk at the waist (a strip 5 % of the height either side of the middle,
  // at 55-65 % of the height), not the mean z of the whole body, which toes,
  // face and hands pull forward: MakeHuman's mean body has its mean z 0.139 m,
  // in front of its belly at 0.134, and no cut enclosed it (crotch NaN).
  const double xmid = 0.5 * (body.col(0).minCoeff() + body.col(0).maxCoeff());
  double front = -std::numeric_limits<double>::infinity(), back = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < body.rows(); ++v)
    if (body(v, 1) >= y0 + 0.55 * h && body(v, 1) <= y0 + 0.65 * h && std::abs(body(v, 0) - xmid) <= 0.05 * h)
      front = std::max(front, body(v, 2)), back = std::min(back, body(v, 2));
  const Eigen::Vector2d centre(xmid, back <= front ? 0.5 * (front + back) : body.col(2).mean());
  for (double f = 0.25; f <= 0.65; f += 0.0025)
    if (horizontal_girth(body, faces, y0 + f * h, centre).found) return f * h;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace drape::geometry
