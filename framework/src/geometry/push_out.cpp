#include <drape/geometry/push_out.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/pseudo_normals.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <limits>
#include <vector>

namespace drape::geometry {
namespace {

constexpr double kRounding = 1e-12;  // m

// A peak through a face (clear_peaks) is looked for this many steps from the
// closest points of the face's corners: the one met, a heavy breast's tip,
// was one step away.
constexpr int kClimbSteps = 8;
// An edge the Lipschitz bound cannot clear is searched only when its nearer
// end, less the body's possible rise above the chord, is within margin / 2:
// the rise is estimated from the turn of the body's normal between the ends'
// closest points (theta) as kEdgeBend * L / 2 * theta, twice the sagitta of
// a circular arc (L * theta / 8). A ridge sharper than the normals at the two
// closest points show is the case this misses (clear_fins then tests every
// edge the ends' distances cannot keep off the body end to end, and moves
// one that crosses). Measured on the regular
// shirt's 78 test drapes of shards 0-9 and 210 posed test bodies: 324 and
// 325 searches per body (1,362 with a reach of 1.5 margins instead, and no
// estimate of the rise), every lift those found (9.5 and 17.0 per body), no
// crossing edge left; at the sagitta itself (0.25) 44 and 68 searches
// missed a fifth to a third of the lifts.
constexpr double kEdgeBend = 0.5;
// A sharp ridge can cross an edge off its middle while the middle stays just
// beyond half the margin: on the human rig's thinnest bodies (BMI 10.5-10.7)
// a 2.3 cm edge crossed the acromion a quarter of the way along, its middle
// 3.3 mm out of a 6 mm margin. Edges whose middle is nearer than this share
// of the margin have their quarter points searched too. Measured on the
// shipped models (drape bench infer, bodies of BMI 35 and 45): 64-236 more
// searches per body (A-pose 481-639 -> 621-875, posed 299-469 -> 363-569),
// the same lifts there; both thin shoulders cleared (a share of 1.0 would
// search 2.3 times as many edges).
constexpr double kQuarterBand = 0.6;
// An edge through a thin fold of the body (clear_fins) is moved off the
// fold's edge a margin at a time, kFinSteps margins at most (6 mm cleared
// the one fold met, a thin man's underarm, in one step), and only when the
// crossed faces' normals sum to more than kFinAgreement (they do not cancel).
constexpr int kFinSteps = 8;
constexpr double kFinAgreement = 0.5;

// One push-out in progress: the garment's vertices, the closest body point
// of each (current after every move), and which vertices moved.
class PushOutRun {
 public:
  PushOutRun(const BodySurface& body, Eigen::MatrixX3d& vertices, const PushOutOptions& options)
      : body_(body), x_(vertices), options_(options), margin_(options.margin), half_(0.5 * options.margin),
        near_(static_cast<std::size_t>(vertices.rows())), moved_(near_.size(), 0), drift_(near_.size(), 0.0),
        unchecked_(near_.size(), 1), in_lifted_(near_.size(), 0), far_(near_.size(), 0),
        // Each search from the face given for its vertex (locate_near: the
        // same answer as locate), when there is one for every vertex.
        hints_(options.closest_faces && options.closest_faces->size() == near_.size() ? options.closest_faces->data()
                                                                                      : nullptr) {
    if (options.edges) near_edge_.assign(options.edges->size(), 0);
    if (options.edges && options.cut_at_reach) {
      search_within_reach();
      return;
    }
    const auto n = static_cast<std::ptrdiff_t>(near_.size());
#pragma omp parallel for schedule(static, 64) if (n >= kParallelSearches)
    for (std::ptrdiff_t i = 0; i < n; ++i) near_[static_cast<std::size_t>(i)] = exact(static_cast<std::size_t>(i));
  }

  // Every vertex nearer the body than the margin (or inside it) onto the
  // level set s = margin; the vertices moved.
  const std::vector<Eigen::Index>& step_vertices() {
    stepped_.clear();
    for (Eigen::Index i = 0; i < x_.rows(); ++i) {
      const SurfacePoint& s = near_[static_cast<std::size_t>(i)];
      // (A vertex a pass put on the level set may come back a rounding error short of it: left alone.)
      if (s.face < 0 || s.signed_distance >= margin_ - kRounding) continue;
      // Along the gradient of s: exact while the closest point stays on the same face, edge or vertex.
      move(i, (margin_ - s.signed_distance) * s.normal);
      unchecked_[static_cast<std::size_t>(i)] = 1;
      stepped_.push_back(i);
    }
    search_again(stepped_);
    return stepped_;
  }

  // Every edge whose midpoint lies nearer the body than half the margin
  // moved out along the body's normal there until it does not, in order, one
  // edge after another (edges share vertices: the result does not depend on
  // the threads); only edges with an end moved since they were last checked.
  // The vertices moved.
  const std::vector<Eigen::Index>& lift_edges(PushOutReport& report) {
    lifted_.clear();
    lifted_edges_.clear();
    for (std::size_t e = 0; e < options_.edges->size(); ++e) {
      const auto [a, b] = (*options_.edges)[e];
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      if (!unchecked_[ua] && !unchecked_[ub]) continue;
      if (cleared_without_search(ua, ub)) continue;
      const Eigen::Vector3d mid = 0.5 * (x_.row(a) + x_.row(b)).transpose();
      SurfacePoint s = body_.locate_near(mid, near_[ua].face >= 0 ? near_[ua].face : near_[ub].face);
      ++report.edges_searched;
      if (s.face >= 0 && s.signed_distance >= half_ - kRounding && s.signed_distance < kQuarterBand * margin_) {
        // The quarter points too (kQuarterBand), and the edge lifted by the lowest of the three.
        for (const double t : {0.25, 0.75}) {
          const Eigen::Vector3d p = ((1.0 - t) * x_.row(a) + t * x_.row(b)).transpose();
          const SurfacePoint q = body_.locate_near(p, s.face);
          ++report.edges_searched;
          if (q.face >= 0 && q.signed_distance < s.signed_distance) s = q;
        }
      }
      if (s.face < 0 || s.signed_distance >= half_ - kRounding) {
        // Searched and near, not lifted: clear_fins tests it whole.
        if (s.face >= 0 && s.signed_distance < margin_ && !near_edge_[e]) near_edge_[e] = 1, near_edges_.push_back(e);
        continue;
      }
      const Eigen::Vector3d step = (half_ - s.signed_distance) * s.normal;
      lifted_edges_.push_back(e);  // (clear_fins looks at the last pass's)
      for (const int v : {a, b}) {
        move(v, step);
        if (!in_lifted_[static_cast<std::size_t>(v)]) in_lifted_[static_cast<std::size_t>(v)] = 1, lifted_.push_back(v);
      }
      ++report.edges_lifted;
    }
    std::fill(unchecked_.begin(), unchecked_.end(), 0);
    for (const Eigen::Index v : lifted_) unchecked_[static_cast<std::size_t>(v)] = 1, in_lifted_[static_cast<std::size_t>(v)] = 0;
    search_again(lifted_);
    return lifted_;
  }

  // Each edge the last pass lifted, or any pass searched and found within
  // the margin without lifting it, that passes through the body: a thin
  // fold of the body (a thin body's underarm) or a sharp ridge (the
  // acromion of a body of BMI 10.5, under a 3.2 cm edge whose ends were 6
  // mm out and whose middle and quarter points 3.9 and 4.4 mm: it went in
  // and out between them) pierces it while the points searched are
  // outside. Lifting along the normal at one point of the fold moves the
  // edge along itself; the fold's two sides face apart, and the
  // sum of the normals of the faces the edge crosses points off the fold's
  // edge. Both ends are moved that way, a margin at a time, until the edge
  // crosses nothing (kFinSteps at most; else they go back). Tested: the
  // last pass's lifts, the near edges, and every other edge that crosses
  // the body by an exact test of each edge its ends' distances cannot keep
  // out (add_edges_that_may_cross). The vertices moved.
  const std::vector<Eigen::Index>& clear_fins(PushOutReport& report) {
    fin_moved_.clear();
    std::vector<int> crossed;
    std::vector<std::size_t> tested = lifted_edges_;
    tested.insert(tested.end(), near_edges_.begin(), near_edges_.end());
    add_edges_that_may_cross(tested, crossed, report);
    std::sort(tested.begin(), tested.end());
    tested.erase(std::unique(tested.begin(), tested.end()), tested.end());
    report.edges_tested_whole += static_cast<int>(tested.size());
    for (const std::size_t e : tested) {
      const auto [a, b] = (*options_.edges)[e];
      crossed.clear();
      body_.faces_crossed(x_.row(a).transpose(), x_.row(b).transpose(), crossed);
      if (crossed.empty()) continue;
      Eigen::Vector3d off_fold = Eigen::Vector3d::Zero();
      for (const int f : crossed) off_fold += face_normal(body_.vertices(), body_.faces(), f);
      // (Normals that cancel: a flat sheet met twice, no side to go to.)
      if (!(off_fold.norm() > kFinAgreement)) continue;
      off_fold.normalize();
      const Eigen::RowVector3d xa = x_.row(a), xb = x_.row(b);
      bool cleared = false;
      for (int step = 1; step <= kFinSteps && !cleared; ++step) {
        x_.row(a) = xa + step * margin_ * off_fold.transpose();
        x_.row(b) = xb + step * margin_ * off_fold.transpose();
        crossed.clear();
        body_.faces_crossed(x_.row(a).transpose(), x_.row(b).transpose(), crossed);
        cleared = crossed.empty();
      }
      if (!cleared) {
        x_.row(a) = xa, x_.row(b) = xb;
        continue;
      }
      ++report.fins_cleared;
      for (const int v : {a, b}) {
        moved_[static_cast<std::size_t>(v)] = 1;
        drift_[static_cast<std::size_t>(v)] += (x_.row(v) - (v == a ? xa : xb)).norm();
        fin_moved_.push_back(v);
      }
    }
    search_again(fin_moved_);
    return fin_moved_;
  }

  // Each garment face a body vertex rises through from below while the
  // face's corners and edges are clear: the
  // tip of a cap the body's mesh draws with long edges (a heavy woman's
  // breast on the human rig: a vertex 0.3 mm through a 4-5 cm face whose
  // corners were 12-20 mm out). The highest body point under a face, seen
  // along its normal, is a vertex (a linear function's maximum over a
  // mesh); it is found by climbing the body's vertices from the corners of
  // the faces closest to the face's own corners, always to the highest
  // neighbour. On a convex cap a vertex no neighbour of which is higher is
  // the highest; a second bump the climb does not reach, or a peak more than
  // kClimbSteps vertices from the corners' closest points, is the case this
  // misses. The climb stays over the face. A face is skipped when a corner
  // is farther from the body than the face's longest edge (every point of
  // the face is within that of each corner), or every corner farther than
  // the longest edge / sqrt(3) (every point is within that of some corner):
  // then no body point reaches it. A face is lifted only where an edge
  // at the peak passes through it (exact) and the body's normal at the peak
  // points the face's way; it moves out along its normal until the peak is
  // half the margin below it. The vertices moved.
  const std::vector<Eigen::Index>& clear_peaks(PushOutReport& report) {
    peak_moved_.clear();
    const Eigen::MatrixX3i& faces = *options_.faces;
    const Eigen::MatrixX3d& body = body_.vertices();
    const Eigen::MatrixX3i& body_faces = body_.faces();
    const VertexAdjacency& ring = body_.vertex_adjacency();
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const std::array<int, 3> corner{faces(f, 0), faces(f, 1), faces(f, 2)};
      const Eigen::Vector3d a = x_.row(corner[0]), b = x_.row(corner[1]), c = x_.row(corner[2]);
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      Eigen::Vector3d outward = Eigen::Vector3d::Zero();
      bool clear = false, any = false;
      double nearest = std::numeric_limits<double>::infinity();
      for (const int v : corner) {
        const SurfacePoint& s = near_[static_cast<std::size_t>(v)];
        if (s.face < 0) continue;
        any = true;
        clear = clear || s.signed_distance > longest;
        nearest = std::min(nearest, s.signed_distance);
        outward += s.normal;
      }
      // (Every point of a triangle is within its longest edge / sqrt(3) of a corner.)
      if (clear || !any || nearest > longest / std::sqrt(3.0)) continue;
      Eigen::Vector3d n = (b - a).cross(c - a);
      if (!(n.norm() > 0)) continue;  // a degenerate face: its edges are its whole surface
      n.normalize();
      if (n.dot(outward) < 0) n = -n;
      const auto height = [&](int v) { return (Eigen::Vector3d(body.row(v)) - a).dot(n); };
      int top = -1;
      double top_height = -std::numeric_limits<double>::infinity();
      for (const int v : corner) {
        const int bf = near_[static_cast<std::size_t>(v)].face;
        if (bf < 0) continue;
        for (int k = 0; k < 3; ++k)
          if (const double h = height(body_faces(bf, k)); h > top_height) top_height = h, top = body_faces(bf, k);
      }
      // The climb stays over the face (its projection within the disc about
      // the face's centroid that holds the corners), kClimbSteps at most.
      const Eigen::Vector3d centroid = (a + b + c) / 3;
      const double reach = std::max({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()});
      const auto over_face = [&](int u) {
        const Eigen::Vector3d d = Eigen::Vector3d(body.row(u)) - centroid;
        return (d - d.dot(n) * n).norm() <= reach;
      };
      for (int step = 0; step < kClimbSteps; ++step) {
        const int from = top;
        for (int k = ring.start[static_cast<std::size_t>(from)]; k < ring.start[static_cast<std::size_t>(from) + 1]; ++k) {
          const int u = ring.neighbours[static_cast<std::size_t>(k)];
          if (const double h = height(u); h > top_height && over_face(u)) top_height = h, top = u;
        }
        if (top == from) break;
      }
      if (top_height <= 0) continue;  // below the face's plane: nothing of the cap reaches it
      // A crossing: an edge at the peak passes through the face (exact) ...
      bool through = false;
      for (int k = ring.start[static_cast<std::size_t>(top)]; k < ring.start[static_cast<std::size_t>(top) + 1] && !through; ++k)
        through = segment_pierces_triangle(body.row(top).transpose(), body.row(ring.neighbours[static_cast<std::size_t>(k)]).transpose(), a, b, c);
      if (!through) continue;
      // ... from below: the body there faces the way the face does. (A part
      // of the body beyond the face, the trunk beside a sleeve, comes through
      // it from above; lifting would push the face into it.)
      if (body_.locate(body.row(top).transpose()).normal.dot(n) <= 0) continue;
      const Eigen::Vector3d step = (top_height + half_) * n;
      for (const int v : corner) {
        move(v, step);
        peak_moved_.push_back(v);
      }
      ++report.peaks_cleared;
    }
    std::sort(peak_moved_.begin(), peak_moved_.end());
    peak_moved_.erase(std::unique(peak_moved_.begin(), peak_moved_.end()), peak_moved_.end());
    search_again(peak_moved_);
    return peak_moved_;
  }

  // The run's figures, and each vertex's closest face for the next body.
  void finish(const Eigen::MatrixX3d& start, PushOutReport& report) const {
    if (options_.closest_faces) {
      options_.closest_faces->resize(near_.size());
      // (In place: a far vertex's entry is its hint, read before this write.)
      for (std::size_t i = 0; i < near_.size(); ++i) (*options_.closest_faces)[i] = far_[i] ? hint(i) : near_[i].face;
    }
    if (x_.rows() > 0) report.largest_move = (x_ - start).rowwise().norm().maxCoeff();
    for (std::size_t i = 0; i < near_.size(); ++i) {
      report.moved += moved_[i];
      report.still_within += near_[i].face >= 0 && near_[i].signed_distance < half_;
      report.beyond_reach += far_[i];
    }
  }

 private:
  void move(Eigen::Index i, const Eigen::Vector3d& step) {
    x_.row(i) += step.transpose();
    moved_[static_cast<std::size_t>(i)] = 1;
    drift_[static_cast<std::size_t>(i)] += step.norm();
  }

  // An edge whose midpoint is surely half the margin out: by the signed
  // distance's Lipschitz bound, or its nearer end less the body's possible
  // rise above the chord (kEdgeBend). Each end's distance is a lower bound:
  // its last search's less how far it moved since (an earlier lift of this
  // pass may have moved it, in any direction). A far end's bound is its reach,
  // which clears the edge unless the other end's step lengthened it; then
  // it is searched in full and the test is the one without reaches.
  bool cleared_without_search(std::size_t a, std::size_t b) {
    const double half_edge = 0.5 * (x_.row(static_cast<Eigen::Index>(a)) - x_.row(static_cast<Eigen::Index>(b))).norm();
    if (far_[a] || far_[b]) {
      const double sa = far_[a] ? reach_[a] : near_[a].signed_distance - drift_[a];
      const double sb = far_[b] ? reach_[b] : near_[b].signed_distance - drift_[b];
      if (std::max(sa, sb) - half_edge >= half_) return true;
      for (const std::size_t i : {a, b})
        if (far_[i]) near_[i] = exact(i), far_[i] = 0;  // not moved since: the search it skipped
    }
    if (near_[a].face < 0 || near_[b].face < 0) return false;
    const double sa = near_[a].signed_distance - drift_[a], sb = near_[b].signed_distance - drift_[b];
    if (std::max(sa, sb) - half_edge >= half_) return true;
    const double turn = std::acos(std::clamp(near_[a].normal.dot(near_[b].normal), -1.0, 1.0));
    return std::min(sa, sb) - kEdgeBend * half_edge * turn >= half_;
  }

  // Every edge not yet in `tested` that passes through the body, found by
  // an exact segment test of each edge the Lipschitz bound cannot keep out:
  // the signed distance falls by at most the distance moved, so an edge
  // whose ends' distances sum to its length or more stays outside. The
  // searches above skip edges by an estimate of the body's rise between
  // their ends (kEdgeBend), and a ridge sharper than the ends' normals show
  // escapes it: on a BMI 11, 2.0 m man (shoulders abducted 25 deg, flexed
  // 45) a 3.2 cm edge 6.8 and 12.5-12.7 mm out at its ends, its normals
  // 24 deg apart, crossed the acromion's ridge 0.4 of the way along. The
  // test costs a segment query per edge near the body (tests/geometry_queries
  // /push_out_test.cpp: the ridge the estimate misses).
  void add_edges_that_may_cross(std::vector<std::size_t>& tested, std::vector<int>& crossed, PushOutReport& report) {
    // A lower bound of each vertex's distance (a far one is beyond its
    // reach; one never located is taken as inside).
    const auto lower = [&](int v) {
      const auto i = static_cast<std::size_t>(v);
      return far_[i] ? reach_[i] : near_[i].face >= 0 ? near_[i].signed_distance - drift_[i] : -1.0;
    };
    std::vector<char> in(options_.edges->size(), 0);
    for (const std::size_t e : tested) in[e] = 1;
    for (std::size_t e = 0; e < options_.edges->size(); ++e) {
      if (in[e]) continue;
      const auto [a, b] = (*options_.edges)[e];
      const double length = (x_.row(a) - x_.row(b)).norm();
      const double la = lower(a), lb = lower(b);
      if (la + lb >= length || !(length > 0)) continue;  // (an edge of no length is a vertex: stepped out)
      // Only the part of the edge outside both ends' clear balls.
      const Eigen::Vector3d xa = x_.row(a).transpose(), along = (x_.row(b) - x_.row(a)).transpose() / length;
      crossed.clear();
      body_.faces_crossed(xa + std::max(la, 0.0) * along, xa + (length - std::max(lb, 0.0)) * along, crossed);
      if (crossed.empty()) ++report.edges_tested_whole;  // (one that crosses is counted with the rest of `tested`)
      else tested.push_back(e);
    }
  }

  int hint(std::size_t i) const { return hints_ ? hints_[i] : -1; }

  // The closest body point of vertex i, searched in full from its hint.
  SurfacePoint exact(std::size_t i) const {
    return body_.locate_near(x_.row(static_cast<Eigen::Index>(i)).transpose(), hint(i));
  }

  // With edges, the first searches go only as far as each vertex's reach:
  // the margin, or half its longest edge plus half the margin, whichever is
  // more. A vertex beyond its reach is neither stepped nor (by the Lipschitz
  // bound) the end of an edge that needs a search, so where its closest
  // point lies does not matter, only its side, and a search cut at the
  // reach visits a few boxes instead of every face within the vertex's
  // distance. (A third of the coarse shirt's vertices on the A-pose model's
  // predictions over the body space; 7 % on the BMI 35-45 posed bodies of
  // drape bench infer, where the shirt is tight.) The side: the signed distance
  // changes by at most an edge's length along it, so a far vertex whose
  // neighbour's distance less their edge is above minus its reach is outside
  // (|s| >= reach); the sign spreads from vertex to vertex over the
  // garment's edges, and a vertex it cannot reach (a part of the garment
  // deep in the body, or all beyond reach) is searched in full.
  void search_within_reach() {
    const std::size_t n = near_.size();
    reach_.assign(n, margin_);
    for (const auto& [a, b] : *options_.edges) {
      const double r = half_ + 0.5 * (x_.row(a) - x_.row(b)).norm();
      for (const int v : {a, b}) reach_[static_cast<std::size_t>(v)] = std::max(reach_[static_cast<std::size_t>(v)], r);
    }
    // A little more than the reach, so that rounding cannot put a face the
    // bound needs beyond the search.
    for (double& r : reach_) r = r * (1 + 1e-6) + 1e-9;

    const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static, 64) if (count >= kParallelSearches)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      near_[k] = body_.locate_near(x_.row(i).transpose(), hint(k), reach_[k]);
    }
    // Beyond reach, side not yet known: nothing found within the reach and
    // not yet far_ (outside) nor searched in full.
    const auto unknown = [&](std::size_t v) { return near_[v].face < 0 && !far_[v]; };
    const VertexAdjacency adjacency = vertex_adjacency(*options_.edges, static_cast<int>(n));
    std::vector<std::size_t> queue;
    queue.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (!unknown(i)) queue.push_back(i);
    std::size_t head = 0, next_unknown = 0;
    for (;;) {
      while (head < queue.size()) {
        const std::size_t v = queue[head++];
        const double lower = far_[v] ? reach_[v] : near_[v].signed_distance;
        for (int k = adjacency.start[v]; k < adjacency.start[v + 1]; ++k) {
          const auto u = static_cast<std::size_t>(adjacency.neighbours[static_cast<std::size_t>(k)]);
          if (!unknown(u)) continue;
          const double length = (x_.row(static_cast<Eigen::Index>(u)) - x_.row(static_cast<Eigen::Index>(v))).norm();
          if (lower - length > -reach_[u]) far_[u] = 1, queue.push_back(u);
        }
      }
      while (next_unknown < n && !unknown(next_unknown)) ++next_unknown;
      if (next_unknown == n) break;
      near_[next_unknown] = exact(next_unknown);
      queue.push_back(next_unknown);
    }
  }

  // Searched again where a vertex moved (only their closest points change),
  // from the face it was nearest before: the same answer, a shorter search.
  void search_again(const std::vector<Eigen::Index>& changed) {
    const auto count = static_cast<std::ptrdiff_t>(changed.size());
#pragma omp parallel for schedule(static, 16) if (count >= kParallelSearches)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const auto i = static_cast<std::size_t>(changed[static_cast<std::size_t>(k)]);
      near_[i] = body_.locate_near(x_.row(static_cast<Eigen::Index>(i)).transpose(), far_[i] ? hint(i) : near_[i].face);
      drift_[i] = 0;
      far_[i] = 0;
    }
  }

  const BodySurface& body_;
  Eigen::MatrixX3d& x_;
  const PushOutOptions& options_;
  const double margin_, half_;
  std::vector<SurfacePoint> near_;
  std::vector<char> moved_;
  std::vector<double> drift_;    // how far each vertex moved since near_ was found for it
  std::vector<char> unchecked_;  // moved since its edges were last checked
  std::vector<char> in_lifted_;
  std::vector<char> far_;        // beyond its reach and outside: no closest point searched
  std::vector<double> reach_;    // with edges: how far each vertex's first search went
  const int* hints_;             // the face each vertex's search starts from (null: none)
  std::vector<Eigen::Index> stepped_, lifted_, fin_moved_, peak_moved_;
  std::vector<std::size_t> lifted_edges_;  // the edges the last lift_edges() lifted
  std::vector<std::size_t> near_edges_;    // edges a search found within the margin and left (any pass)
  std::vector<char> near_edge_;            // per edge: in near_edges_
};

}  // namespace

PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices, double margin, int max_passes,
                       std::vector<int>* closest_faces) {
  PushOutOptions options;
  options.margin = margin;
  options.max_passes = max_passes;
  options.closest_faces = closest_faces;
  return push_out(body, vertices, options);
}

PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices, const PushOutOptions& options) {
  if (!(options.margin >= 0) || !std::isfinite(options.margin)) throw Error("push_out: the margin must be finite and >= 0");
  if (options.max_passes < 1) throw Error("push_out: at least one pass");
  if (!vertices.allFinite()) throw Error("push_out: the garment has a non-finite vertex");
  if (options.edges)
    for (const auto& [a, b] : *options.edges)
      if (a < 0 || b < 0 || a >= vertices.rows() || b >= vertices.rows())
        throw Error("push_out: edge (" + std::to_string(a) + ", " + std::to_string(b) + ") outside the garment's " +
                    std::to_string(vertices.rows()) + " vertices");
  if (options.faces && options.faces->size() > 0 &&
      (options.faces->minCoeff() < 0 || options.faces->maxCoeff() >= vertices.rows()))
    throw Error("push_out: a face's corner lies outside the garment's " + std::to_string(vertices.rows()) + " vertices");
  PushOutReport report;
  const Eigen::MatrixX3d start = vertices;
  PushOutRun run(body, vertices, options);
  for (int pass = 0; pass < options.max_passes; ++pass) {
    ++report.passes;
    const bool stepped = !run.step_vertices().empty();
    // Edges not in the last pass: a lift can move a vertex into another part
    // of the body (a crease), and the vertices' clearance is the promise
    // (p = 0); the edges' is the best the passes before it reached.
    const bool lifted = options.edges && pass + 1 < options.max_passes && !run.lift_edges(report).empty();
    if (!stepped && !lifted) break;  // nothing moved: the last search still holds
  }
  // Edges through a thin fold, faces a peak of the body rises through, then
  // the vertices' margin kept once more.
  const bool fins = options.edges && !run.clear_fins(report).empty();
  const bool peaks = options.edges && options.faces && !run.clear_peaks(report).empty();
  if (fins || peaks) run.step_vertices();
  run.finish(start, report);
  return report;
}

}  // namespace drape::geometry
