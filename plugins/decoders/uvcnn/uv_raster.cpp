#include "uv_raster.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/hierarchy.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace drape::uvcnn {
namespace {

// Pixels between a chart and its tile's edge: bilinear footprints (one pixel
// either way) of two neighbouring charts then never reach the same pixel centre.
constexpr double kBorder = 1.5;
// Below this total splat weight a pixel counts as not reached.
constexpr double kMinSplat = 1e-6;

struct Bilinear {
  int pixel[4];
  double weight[4];
};

// Pixel (row, col) covers [col, col + 1] x [row, row + 1]; its centre is at +0.5.
Bilinear bilinear(const Eigen::Vector2d& p, int res) {
  const double fx = p.x() - 0.5, fy = p.y() - 0.5;
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, res - 2);
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, res - 2);
  const double tx = std::clamp(fx - i0, 0.0, 1.0), ty = std::clamp(fy - j0, 0.0, 1.0);
  return {{j0 * res + i0, j0 * res + i0 + 1, (j0 + 1) * res + i0, (j0 + 1) * res + i0 + 1},
          {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty}};
}

}  // namespace

UvRaster build_uv_raster(const Mesh& m, int res) {
  if (!m.has_uv()) throw ConfigError("the garment template has no UV coordinates to lay out in an image");
  if (res < 4) throw ConfigError("the UV image needs at least 4x4 pixels, got " + std::to_string(res));
  const int nv = m.num_vertices(), nf = m.num_faces();
  UvRaster r;
  r.resolution = res;
  const Eigen::VectorXi face_chart = geometry::uv_charts(m, r.charts);

  // Points: one per (UV index, chart); a seam vertex has one in each chart.
  std::map<std::pair<int, int>, int> point_of;
  std::vector<int> point_vertex, point_chart;
  std::vector<Eigen::Vector2d> point_uv;
  Eigen::MatrixX3i corner_point(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int t = m.uv_faces(f, k);
      if (t < 0 || t >= m.uv.rows() || m.faces(f, k) < 0 || m.faces(f, k) >= nv)
        throw ConfigError("garment face " + std::to_string(f) + " has an index out of range");
      const auto [it, added] = point_of.try_emplace({t, face_chart[f]}, static_cast<int>(point_vertex.size()));
      if (added) {
        point_vertex.push_back(m.faces(f, k));
        point_chart.push_back(face_chart[f]);
        point_uv.push_back(m.uv.row(t).transpose());
      }
      corner_point(f, k) = it->second;
    }

  // Chart boxes, then the grid of tiles that allows the largest common scale.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d> lo(r.charts, Eigen::Vector2d(inf, inf)), hi(r.charts, Eigen::Vector2d(-inf, -inf));
  for (std::size_t p = 0; p < point_uv.size(); ++p) {
    lo[point_chart[p]] = lo[point_chart[p]].cwiseMin(point_uv[p]);
    hi[point_chart[p]] = hi[point_chart[p]].cwiseMax(point_uv[p]);
  }
  for (int c = 0; c < r.charts; ++c)
    if (!((hi[c] - lo[c]).minCoeff() > 0) || !(hi[c] - lo[c]).allFinite())
      throw ConfigError("UV chart " + std::to_string(c) + " has no area to lay out");
  double best = 0.0;
  for (int rows = 1; rows <= r.charts; ++rows) {
    const int cols = (r.charts + rows - 1) / rows;
    const double tw = double(res) / cols - 2 * kBorder, th = double(res) / rows - 2 * kBorder;
    double s = inf;
    for (int c = 0; c < r.charts; ++c) s = std::min({s, tw / (hi[c] - lo[c]).x(), th / (hi[c] - lo[c]).y()});
    if (s > best) best = s, r.grid_rows = rows, r.grid_cols = cols;
  }
  if (!(best > 0))
    throw ConfigError("a " + std::to_string(res) + "x" + std::to_string(res) + " image is too small for " +
                      std::to_string(r.charts) + " UV charts");
  r.pixels_per_meter = best;
  const double tw = double(res) / r.grid_cols, th = double(res) / r.grid_rows;
  std::vector<Eigen::Vector2d> position(point_uv.size());
  for (std::size_t p = 0; p < point_uv.size(); ++p) {
    const int c = point_chart[p];
    const Eigen::Vector2d origin((c % r.grid_cols) * tw, (c / r.grid_cols) * th);
    const Eigen::Vector2d centring = 0.5 * (Eigen::Vector2d(tw, th) - best * (hi[c] - lo[c]));
    position[p] = origin + centring + best * (point_uv[p] - lo[c]);
  }

  // Rasterise: normalised bilinear splats, barycentric fill of the pixels no splat reaches.
  const int pixels = res * res;
  std::vector<Eigen::Triplet<double>> splats;
  Eigen::VectorXd reach = Eigen::VectorXd::Zero(pixels);
  for (std::size_t p = 0; p < position.size(); ++p) {
    const Bilinear b = bilinear(position[p], res);
    for (int k = 0; k < 4; ++k) {
      splats.emplace_back(b.pixel[k], point_vertex[p], b.weight[k]);
      reach[b.pixel[k]] += b.weight[k];
    }
  }
  std::vector<Eigen::Triplet<float>> raster;
  for (const auto& t : splats)
    if (reach[t.row()] > kMinSplat) raster.emplace_back(t.row(), t.col(), static_cast<float>(t.value() / reach[t.row()]));
  std::vector<bool> filled(pixels);
  for (int q = 0; q < pixels; ++q) filled[q] = reach[q] > kMinSplat;
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector2d a = position[corner_point(f, 0)], b = position[corner_point(f, 1)], c = position[corner_point(f, 2)];
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (area == 0.0) continue;
    const Eigen::Vector2d boxlo = a.cwiseMin(b).cwiseMin(c), boxhi = a.cwiseMax(b).cwiseMax(c);
    for (int j = std::max(0, int(std::ceil(boxlo.y() - 0.5))); j <= std::min(res - 1, int(std::floor(boxhi.y() - 0.5))); ++j)
      for (int i = std::max(0, int(std::ceil(boxlo.x() - 0.5))); i <= std::min(res - 1, int(std::floor(boxhi.x() - 0.5))); ++i) {
        const int q = j * res + i;
        if (filled[q]) continue;
        const Eigen::Vector2d p(i + 0.5, j + 0.5);
        auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
        const double wa = cross(b - p, c - p) / area, wb = cross(c - p, a - p) / area, wc = 1.0 - wa - wb;
        if (wa < -1e-12 || wb < -1e-12 || wc < -1e-12) continue;
        raster.emplace_back(q, m.faces(f, 0), static_cast<float>(wa));
        raster.emplace_back(q, m.faces(f, 1), static_cast<float>(wb));
        raster.emplace_back(q, m.faces(f, 2), static_cast<float>(wc));
        filled[q] = true;
      }
  }
  r.covered_pixels = static_cast<int>(std::count(filled.begin(), filled.end(), true));
  r.rasterise.resize(pixels, nv);
  r.rasterise.setFromTriplets(raster.begin(), raster.end());

  // Sample: bilinear at every position of a vertex, averaged over them.
  std::vector<int> positions_of(nv, 0);
  for (int v : point_vertex) ++positions_of[v];
  std::vector<Eigen::Triplet<float>> sampling;
  for (std::size_t p = 0; p < position.size(); ++p) {
    const Bilinear b = bilinear(position[p], res);
    const double share = 1.0 / positions_of[point_vertex[p]];
    for (int k = 0; k < 4; ++k) sampling.emplace_back(point_vertex[p], b.pixel[k], static_cast<float>(share * b.weight[k]));
  }
  r.sample.resize(nv, pixels);
  r.sample.setFromTriplets(sampling.begin(), sampling.end());
  return r;
}

}  // namespace drape::uvcnn
