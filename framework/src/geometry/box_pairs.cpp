// Overlapping box pairs through a uniform grid over one side's boxes.
//
// Each pair is reported once, in one cell only: the cell holding the low
// corner of the pair's intersection, max(a.lo, b.lo). Per axis that cell is
// max(cell(a.lo), cell(b.lo)) because the cell index is monotone in the
// coordinate, so the test is a few integer comparisons and no pair needs a
// hash set or a global sort to remove duplicates.
#include <drape/geometry/box_pairs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace drape::geometry {
namespace {

using Cell = std::array<int, 3>;

bool valid(const Box& x) {
  return x.lo.allFinite() && x.hi.allFinite() && (x.lo.array() <= x.hi.array()).all();
}

bool overlap(const Box& x, const Box& y) {
  return (x.lo.array() <= y.hi.array()).all() && (y.lo.array() <= x.hi.array()).all();
}

// Cells of size `cell` from `origin`, dims[k] along each axis. Coordinates
// outside are clamped to the border cells: every box of the grid lies inside,
// so a query box sticking out misses nothing.
struct Grid {
  Eigen::Vector3d origin;
  double cell = 1;
  Cell dims{1, 1, 1};

  Cell cell_of(const Eigen::Vector3d& p) const {
    Cell c;
    for (std::size_t k = 0; k < 3; ++k) {
      const double q = std::floor((p[static_cast<Eigen::Index>(k)] - origin[static_cast<Eigen::Index>(k)]) / cell);
      c[k] = static_cast<int>(std::clamp(q, 0.0, static_cast<double>(dims[k] - 1)));
    }
    return c;
  }
  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * static_cast<std::size_t>(dims[1]) + static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(dims[0]) +
           static_cast<std::size_t>(x);
  }
  std::size_t size() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  }
};

// The median of the boxes' largest extents: about one face per cell for a mesh.
double median_extent(const std::vector<Box>& boxes, const std::vector<int>& ids) {
  std::vector<double> extent;
  extent.reserve(ids.size());
  for (int j : ids) extent.push_back((boxes[static_cast<std::size_t>(j)].hi - boxes[static_cast<std::size_t>(j)].lo).maxCoeff());
  const auto middle = extent.begin() + static_cast<std::ptrdiff_t>(extent.size() / 2);
  std::nth_element(extent.begin(), middle, extent.end());
  return *middle;
}

// A grid over the given boxes' bounds with about the requested cell size, but
// never more than a few cells per box (memory stays linear even for tiny
// cells or boxes spread far apart).
Grid make_grid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell, std::size_t box_count) {
  const Eigen::Vector3d extent = hi - lo;
  // Points only, or all in one spot: any positive size will do.
  if (!(cell > 0)) cell = extent.maxCoeff() / std::cbrt(static_cast<double>(box_count));
  if (!(cell > 0)) cell = 1;
  const double max_cells = std::max(4096.0, 8.0 * static_cast<double>(box_count));
  Grid grid;
  grid.origin = lo;
  for (;;) {
    double cells = 1;
    for (Eigen::Index k = 0; k < 3; ++k) cells *= std::floor(extent[k] / cell) + 1;
    if (cells <= max_cells) break;
    cell *= 1.01 * std::cbrt(cells / max_cells);
  }
  grid.cell = cell;
  for (std::size_t k = 0; k < 3; ++k)
    grid.dims[k] = static_cast<int>(std::floor(extent[static_cast<Eigen::Index>(k)] / cell)) + 1;
  return grid;
}

// The box of the primitive's vertices in x, and in x_end too when given (the
// box it sweeps over a linear move), grown by `inflate`.
template <std::size_t K>
Box primitive_box(const std::array<int, K>& v, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end, double inflate) {
  Box box{x.row(v[0]).transpose(), x.row(v[0]).transpose()};
  for (std::size_t k = 0; k < K; ++k) {
    box.lo = box.lo.cwiseMin(x.row(v[k]).transpose());
    box.hi = box.hi.cwiseMax(x.row(v[k]).transpose());
    if (x_end) {
      box.lo = box.lo.cwiseMin(x_end->row(v[k]).transpose());
      box.hi = box.hi.cwiseMax(x_end->row(v[k]).transpose());
    }
  }
  box.lo.array() -= inflate;
  box.hi.array() += inflate;
  return box;
}

}  // namespace

BoxGrid::BoxGrid(std::vector<Box> boxes, double cell_size) : boxes_(std::move(boxes)) {
  std::vector<int> in_grid;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (std::size_t j = 0; j < boxes_.size(); ++j)
    if (valid(boxes_[j])) {
      in_grid.push_back(static_cast<int>(j));
      lo = lo.cwiseMin(boxes_[j].lo), hi = hi.cwiseMax(boxes_[j].hi);
    }
  start_.assign(2, 0);
  if (in_grid.empty()) return;
  bounds_ = {lo, hi};
  Grid grid = make_grid(lo, hi, cell_size > 0 ? cell_size : median_extent(boxes_, in_grid), in_grid.size());
  // Boxes much larger than the cells (a mix of sizes) would each fill many
  // cells: coarsen until the cell lists hold a few entries per box.
  const double max_entries = 16.0 * static_cast<double>(in_grid.size()) + 4096.0;
  for (;;) {
    double entries = 0;
    for (int j : in_grid) {
      const Cell c0 = grid.cell_of(boxes_[static_cast<std::size_t>(j)].lo), c1 = grid.cell_of(boxes_[static_cast<std::size_t>(j)].hi);
      double covered = 1;
      for (std::size_t k = 0; k < 3; ++k) covered *= c1[k] - c0[k] + 1;
      entries += covered;
    }
    if (entries <= max_entries || grid.size() == 1) break;
    grid = make_grid(lo, hi, 2 * grid.cell, in_grid.size());
  }
  origin_ = grid.origin, cell_ = grid.cell, dims_ = grid.dims;

  // Compressed cell lists (counting sort), each item with the box's low cell
  // inline, so the duplicate test reads memory in order.
  start_.assign(grid.size() + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < grid.size(); ++c) start_[c + 1] += start_[c];
      items_.resize(static_cast<std::size_t>(start_.back()));
      fill.assign(start_.begin(), start_.end() - 1);
    }
    for (int j : in_grid) {
      const auto js = static_cast<std::size_t>(j);
      const Cell c0 = grid.cell_of(boxes_[js].lo), c1 = grid.cell_of(boxes_[js].hi);
      for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
          for (int x = c0[0]; x <= c1[0]; ++x) {
            const std::size_t c = grid.index(x, y, z);
            if (pass == 0) ++start_[c + 1];
            else items_[static_cast<std::size_t>(fill[c]++)] = {j, c0};
          }
    }
  }
}

std::array<int, 3> BoxGrid::cell_of(const Eigen::Vector3d& p) const {
  return Grid{origin_, cell_, dims_}.cell_of(p);
}

std::size_t BoxGrid::index(int x, int y, int z) const { return Grid{origin_, cell_, dims_}.index(x, y, z); }

std::vector<std::pair<int, int>> BoxGrid::overlapping(const std::vector<Box>& a) const {
  std::vector<std::pair<int, int>> pairs;
  if (a.empty() || items_.empty()) return pairs;
  // Fixed chunks of a, each with its own output, joined in order: the result
  // is the same for any number of threads.
  constexpr int chunk = 256;
  const int na = static_cast<int>(a.size()), chunks = (na + chunk - 1) / chunk;
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1) if (chunks > 1)
  for (int k = 0; k < chunks; ++k) {
    std::vector<int> hits;
    auto& out = found[static_cast<std::size_t>(k)];
    for (int i = k * chunk; i < std::min(na, (k + 1) * chunk); ++i) {
      const Box& q = a[static_cast<std::size_t>(i)];
      if (!valid(q) || !overlap(q, bounds_)) continue;
      const Cell c0 = cell_of(q.lo), c1 = cell_of(q.hi);
      hits.clear();
      for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
          for (int x = c0[0]; x <= c1[0]; ++x) {
            const std::size_t c = index(x, y, z);
            for (int s = start_[c]; s < start_[c + 1]; ++s) {
              const Item& item = items_[static_cast<std::size_t>(s)];
              const Cell& l = item.low;
              // Only in the cell of the intersection's low corner (see the top).
              if (x != std::max(c0[0], l[0]) || y != std::max(c0[1], l[1]) || z != std::max(c0[2], l[2])) continue;
              if (overlap(q, boxes_[static_cast<std::size_t>(item.box)])) hits.push_back(item.box);
            }
          }
      std::sort(hits.begin(), hits.end());
      for (int j : hits) out.emplace_back(i, j);
    }
  }
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs.reserve(total);
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  return pairs;
}

bool boxes_overlap(const Box& a, const Box& b) { return valid(a) && valid(b) && overlap(a, b); }

bool sweep_within(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, double inflate) {
  if (x0.rows() != x.rows() || dx.rows() != x.rows() || x.rows() == 0) return false;
  if (!x0.allFinite() || !x.allFinite() || !dx.allFinite()) return false;  // (Eigen's maxCoeff may pass over a NaN)
  const double drift = (x - x0).cwiseAbs().maxCoeff(), step = dx.cwiseAbs().maxCoeff();
  // The boxes' corners are rounded sums (x0 - inflate, x + dx): a few ulps of
  // the largest coordinate each, far below the nanometre kept in hand.
  const double rounding = 8 * std::numeric_limits<double>::epsilon() * (x0.cwiseAbs().maxCoeff() + x.cwiseAbs().maxCoeff() + step);
  return drift + step <= inflate - 1e-9 - rounding;
}

std::vector<std::pair<int, int>> overlapping_boxes(const std::vector<Box>& a, const std::vector<Box>& b,
                                                   double cell_size) {
  if (a.empty()) return {};
  return BoxGrid(b, cell_size).overlapping(a);
}

MeshBoxes mesh_boxes(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end, const Eigen::MatrixX3i& faces,
                     const std::vector<std::array<int, 2>>& edges, double inflate) {
  MeshBoxes b;
  b.points.resize(static_cast<std::size_t>(x.rows()));
  b.faces.resize(static_cast<std::size_t>(faces.rows()));
  b.edges.resize(edges.size());
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    b.points[static_cast<std::size_t>(v)] = primitive_box(std::array<int, 1>{static_cast<int>(v)}, x, x_end, inflate);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    b.faces[static_cast<std::size_t>(f)] =
        primitive_box(std::array<int, 3>{faces(f, 0), faces(f, 1), faces(f, 2)}, x, x_end, inflate);
  for (std::size_t e = 0; e < edges.size(); ++e) b.edges[e] = primitive_box(edges[e], x, x_end, inflate);
  return b;
}

}  // namespace drape::geometry
