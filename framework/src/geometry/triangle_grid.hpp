#pragma once
// A uniform grid over the triangles of one mesh (internal to the geometry
// layer): the queries of the measurements, surface_crossings and
// self_intersections, and the rays of winding_numbers. The contact's broad
// phase (box_pairs.hpp) is separate on purpose: a count meant to check the
// contact shares no code with it.
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace drape::geometry {

// The triangles of one mesh, each listed in the grid cells its bounding box
// covers. Cells are about twice the mean triangle extent (at most ~256 per
// axis), so a query box of an edge of similar size meets a few cells of a few
// triangles each.
class TriangleGrid {
 public:
  TriangleGrid(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
    const auto nf = static_cast<std::size_t>(faces.rows());
    if (nf == 0) return;
    lo_.resize(nf), hi_.resize(nf);
    box_lo_ = Eigen::Vector3d::Constant(INFINITY), box_hi_ = -box_lo_;
    double mean_extent = 0;
    for (std::size_t f = 0; f < nf; ++f) {
      const auto row = static_cast<Eigen::Index>(f);
      Eigen::Vector3d l = vertices.row(faces(row, 0)), h = l;
      for (int k = 1; k < 3; ++k) {
        l = l.cwiseMin(vertices.row(faces(row, k)).transpose());
        h = h.cwiseMax(vertices.row(faces(row, k)).transpose());
      }
      lo_[f] = l, hi_[f] = h;
      box_lo_ = box_lo_.cwiseMin(l), box_hi_ = box_hi_.cwiseMax(h);
      mean_extent += (h - l).maxCoeff();
    }
    mean_extent /= static_cast<double>(nf);
    cell_ = std::max({2 * mean_extent, (box_hi_ - box_lo_).maxCoeff() / 256, 1e-12});
    for (int k = 0; k < 3; ++k)
      dims_[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(std::floor((box_hi_[k] - box_lo_[k]) / cell_));

    std::vector<std::pair<std::int64_t, int>> entries;
    for (std::size_t f = 0; f < nf; ++f) {
      const auto a = cell_of(lo_[f]), b = cell_of(hi_[f]);
      for (auto x = a[0]; x <= b[0]; ++x)
        for (auto y = a[1]; y <= b[1]; ++y)
          for (auto z = a[2]; z <= b[2]; ++z) entries.emplace_back(key(x, y, z), static_cast<int>(f));
    }
    std::sort(entries.begin(), entries.end());
    // Compressed rows: the faces of cell keys_[i] are faces_[starts_[i] .. starts_[i + 1]).
    for (const auto& [cell_key, face] : entries) {
      if (keys_.empty() || keys_.back() != cell_key) keys_.push_back(cell_key), starts_.push_back(faces_.size());
      faces_.push_back(face);
    }
    starts_.push_back(faces_.size());
  }

  // Face f's bounding box.
  const Eigen::Vector3d& lo(int f) const { return lo_[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& hi(int f) const { return hi_[static_cast<std::size_t>(f)]; }

  // Calls visit(face) once for each triangle whose box overlaps [lo, hi] until
  // visit returns true; returns whether one did.
  template <class Visit>
  bool find(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) const {
    if (keys_.empty() || (hi.array() < box_lo_.array()).any() || (lo.array() > box_hi_.array()).any()) return false;
    const auto a = cell_of(lo.cwiseMax(box_lo_)), b = cell_of(hi.cwiseMin(box_hi_));
    for (auto x = a[0]; x <= b[0]; ++x)
      for (auto y = a[1]; y <= b[1]; ++y)
        for (auto z = a[2]; z <= b[2]; ++z) {
          const std::int64_t k = key(x, y, z);
          const auto it = std::lower_bound(keys_.begin(), keys_.end(), k);
          if (it == keys_.end() || *it != k) continue;
          const auto row = static_cast<std::size_t>(it - keys_.begin());
          for (std::size_t i = starts_[row]; i < starts_[row + 1]; ++i) {
            const int f = faces_[i];
            const auto fs = static_cast<std::size_t>(f);
            if ((hi_[fs].array() < lo.array()).any() || (hi.array() < lo_[fs].array()).any()) continue;
            // Visit a face only in the first cell both boxes cover, so once.
            const auto first = cell_of(lo.cwiseMax(lo_[fs]));
            if (key(first[0], first[1], first[2]) != k) continue;
            if (visit(f)) return true;
          }
        }
    return false;
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& p) const {
    std::array<std::int64_t, 3> c{};
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::int64_t>(std::floor((p[k] - box_lo_[k]) / cell_));
      c[static_cast<std::size_t>(k)] = std::clamp<std::int64_t>(i, 0, dims_[static_cast<std::size_t>(k)]);
    }
    return c;
  }
  std::int64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return (x * (dims_[1] + 1) + y) * (dims_[2] + 1) + z;
  }

  std::vector<Eigen::Vector3d> lo_, hi_;  // per face
  Eigen::Vector3d box_lo_, box_hi_;
  double cell_ = 1;
  std::array<std::int64_t, 3> dims_{};  // the last cell index per axis
  std::vector<std::int64_t> keys_;
  std::vector<std::size_t> starts_;
  std::vector<int> faces_;
};

}  // namespace drape::geometry
