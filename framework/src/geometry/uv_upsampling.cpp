// UV charts and the barycentric up-sampling matrices between hierarchy levels.
#include <drape/errors.hpp>
#include <drape/geometry/hierarchy.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace drape::geometry {
namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

struct Located {
  int face = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

// Barycentric coordinates of p in (a, b, c); false for a degenerate triangle.
bool barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 Eigen::Vector3d& w) {
  const Eigen::Vector2d e0 = b - a, e1 = c - a, d = p - a;
  const double det = e0.x() * e1.y() - e0.y() * e1.x();
  if (det == 0) return false;
  w[1] = (d.x() * e1.y() - d.y() * e1.x()) / det;
  w[2] = (e0.x() * d.y() - e0.y() * d.x()) / det;
  w[0] = 1.0 - w[1] - w[2];
  return true;
}

// Closest point of the triangle to p, as clamped barycentric weights; returns
// the squared distance.
double closest_on_triangle(const Eigen::Vector2d& p, const std::array<Eigen::Vector2d, 3>& t, Eigen::Vector3d& w) {
  if (barycentric(p, t[0], t[1], t[2], w) && w.minCoeff() >= 0) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& a = t[k];
    const Eigen::Vector2d& b = t[(k + 1) % 3];
    const double len2 = (b - a).squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
    const double d2 = (a + s * (b - a) - p).squaredNorm();
    if (d2 < best) {
      best = d2;
      w.setZero();
      w[k] = 1.0 - s;
      w[(k + 1) % 3] = s;
    }
  }
  return best;
}

// Coarse triangles bucketed on a uniform grid over their UV bounding boxes.
class UvGrid {
 public:
  UvGrid(const Mesh& coarse) : mesh_(coarse) {
    lo_ = coarse.uv.colwise().minCoeff().transpose();
    const Eigen::Vector2d hi = coarse.uv.colwise().maxCoeff().transpose();
    cells_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(coarse.num_faces()))));
    size_ = ((hi - lo_) / cells_).cwiseMax(1e-300);
    buckets_.assign(static_cast<std::size_t>(cells_) * cells_, {});
    for (int f = 0; f < coarse.num_faces(); ++f) {
      Eigen::Vector2d a = coarse.uv.row(coarse.uv_faces(f, 0)), b = a;
      for (int k = 1; k < 3; ++k) {
        a = a.cwiseMin(coarse.uv.row(coarse.uv_faces(f, k)).transpose());
        b = b.cwiseMax(coarse.uv.row(coarse.uv_faces(f, k)).transpose());
      }
      const auto [x0, y0] = cell(a);
      const auto [x1, y1] = cell(b);
      for (int x = x0; x <= x1; ++x)
        for (int y = y0; y <= y1; ++y) buckets_[x * cells_ + y].push_back(f);
    }
  }
  std::pair<int, int> cell(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d c = (p - lo_).cwiseQuotient(size_);
    return {std::clamp(static_cast<int>(std::floor(c.x())), 0, cells_ - 1),
            std::clamp(static_cast<int>(std::floor(c.y())), 0, cells_ - 1)};
  }
  const std::vector<int>& candidates(const Eigen::Vector2d& p) const {
    const auto [x, y] = cell(p);
    return buckets_[x * cells_ + y];
  }

 private:
  const Mesh& mesh_;
  Eigen::Vector2d lo_, size_;
  int cells_ = 1;
  std::vector<std::vector<int>> buckets_;
};

}  // namespace

Eigen::VectorXi uv_charts(const Mesh& mesh, int& num_charts) {
  const int nf = mesh.num_faces();
  // Each directed corner pair (vertex a -> b) with its UVs; two faces share a
  // chart when they run the same edge with the same UV indices.
  struct HalfEdge {
    int lo, hi, face, uv_lo, uv_hi;
  };
  std::vector<HalfEdge> edges;
  edges.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      int ta = mesh.uv_faces(f, k), tb = mesh.uv_faces(f, (k + 1) % 3);
      if (a > b) std::swap(a, b), std::swap(ta, tb);
      edges.push_back({a, b, f, ta, tb});
    }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.uv_lo, x.uv_hi) < std::tie(y.lo, y.hi, y.uv_lo, y.uv_hi);
  });
  std::vector<int> parent(nf);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 1; i < edges.size(); ++i) {
    const HalfEdge &x = edges[i - 1], &y = edges[i];
    if (x.lo == y.lo && x.hi == y.hi && x.uv_lo == y.uv_lo && x.uv_hi == y.uv_hi)
      parent[find_root(parent, x.face)] = find_root(parent, y.face);
  }
  std::vector<int> label(nf, -1);
  num_charts = 0;
  Eigen::VectorXi chart(nf);
  for (int f = 0; f < nf; ++f) {
    const int r = find_root(parent, f);
    if (label[r] < 0) label[r] = num_charts++;
    chart[f] = label[r];
  }
  return chart;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> uv_upsampling(const Mesh& fine, const Eigen::VectorXi& fine_face_chart,
                                                           const Mesh& coarse, const Eigen::VectorXi& coarse_face_chart,
                                                           const Eigen::VectorXi& coarse_in_fine) {
  const int n = fine.num_vertices();
  if (fine_face_chart.size() != fine.num_faces() || coarse_face_chart.size() != coarse.num_faces() ||
      coarse_in_fine.size() != coarse.num_vertices())
    throw Error("uv_upsampling: chart or index arrays do not match the meshes");
  const int num_charts = 1 + std::max(fine_face_chart.maxCoeff(), coarse_face_chart.size() ? coarse_face_chart.maxCoeff() : 0);

  // Every fine vertex's distinct (UV, chart) corners: one per chart side of a seam.
  std::vector<std::vector<std::pair<int, int>>> vertex_uvs(n);
  for (int f = 0; f < fine.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> corner{fine.uv_faces(f, k), fine_face_chart[f]};
      auto& list = vertex_uvs[fine.faces(f, k)];
      if (std::find(list.begin(), list.end(), corner) == list.end()) list.push_back(corner);
    }
  std::vector<int> fine_to_coarse(n, -1);
  for (int j = 0; j < coarse_in_fine.size(); ++j) fine_to_coarse[coarse_in_fine[j]] = j;
  const std::vector<int> face_chart(coarse_face_chart.data(), coarse_face_chart.data() + coarse_face_chart.size());
  std::vector<std::vector<int>> chart_faces(num_charts);
  for (int f = 0; f < coarse.num_faces(); ++f) chart_faces[face_chart[f]].push_back(f);

  const UvGrid grid(coarse);
  auto corners = [&](int f) {
    return std::array<Eigen::Vector2d, 3>{coarse.uv.row(coarse.uv_faces(f, 0)), coarse.uv.row(coarse.uv_faces(f, 1)),
                                          coarse.uv.row(coarse.uv_faces(f, 2))};
  };
  auto locate = [&](const Eigen::Vector2d& p, int c) {
    Located best;
    double best_min = -std::numeric_limits<double>::infinity();
    for (int f : grid.candidates(p)) {
      if (face_chart[f] != c) continue;
      const auto t = corners(f);
      Eigen::Vector3d w;
      if (barycentric(p, t[0], t[1], t[2], w) && w.minCoeff() > best_min) {
        best_min = w.minCoeff();
        best = {f, w};
      }
    }
    if (best.face >= 0 && best_min >= -1e-9) {
      best.weights = best.weights.cwiseMax(0.0);
      best.weights /= best.weights.sum();
      return best;
    }
    // Outside every coarse triangle of its chart (the coarse boundary cuts
    // inside a convex bulge): take the closest one, weights clamped.
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int f : chart_faces[c]) {
      Eigen::Vector3d w;
      const double d2 = closest_on_triangle(p, corners(f), w);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = {f, w};
      }
    }
    return best;
  };

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    if (fine_to_coarse[i] >= 0) {
      triplets.emplace_back(i, fine_to_coarse[i], 1.0);
      continue;
    }
    const auto& uvs = vertex_uvs[i];
    if (uvs.empty()) throw Error("uv_upsampling: fine vertex " + std::to_string(i) + " is in no face and not in the coarse mesh");
    // A seam vertex lies on the seam in every chart it belongs to; averaging
    // its charts' weights keeps the up-sampling symmetric across the seam.
    for (const auto& [t, c] : uvs) {
      if (chart_faces[c].empty())
        throw Error("uv_upsampling: UV chart " + std::to_string(c) + " has no triangle in the coarse mesh");
      const Located hit = locate(fine.uv.row(t), c);
      for (int k = 0; k < 3; ++k)
        if (hit.weights[k] > 0)
          triplets.emplace_back(i, coarse.faces(hit.face, k), hit.weights[k] / static_cast<double>(uvs.size()));
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> up(n, coarse.num_vertices());
  up.setFromTriplets(triplets.begin(), triplets.end());
  return up;
}

}  // namespace drape::geometry
