#include <drape/geometry/push_out.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <vector>

namespace drape::geometry {
namespace {

constexpr double kRounding = 1e-12;  // m
// An edge the Lipschitz bound cannot clear is searched only when its nearer
// end, less the body's possible rise above the chord, is within margin / 2:
// the rise is estimated from the turn of the body's normal between the ends'
// closest points (theta) as kEdgeBend * L / 2 * theta, twice the sagitta of
// a circular arc (L * theta / 8). A ridge sharper than the normals at the two
// closest points show is the case this misses. Measured on the regular
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

// One push-out in progress: the garment's vertices, the closest body point
// of each (current after every move), and which vertices moved.
class PushOutRun {
 public:
  PushOutRun(const BodySurface& body, Eigen::MatrixX3d& vertices, const PushOutOptions& options)
      : body_(body), x_(vertices), options_(options), margin_(options.margin), half_(0.5 * options.margin),
        near_(static_cast<std::size_t>(vertices.rows())), moved_(near_.size(), 0), drift_(near_.size(), 0.0),
        unchecked_(near_.size(), 1), in_lifted_(near_.size(), 0) {
    // Each search from the face given for its vertex (locate_near: the same
    // answer as locate, -1 for none).
    const std::vector<int>* hints = options.closest_faces;
    const bool hinted = hints && hints->size() == near_.size();
    const auto n = static_cast<std::ptrdiff_t>(near_.size());
#pragma omp parallel for schedule(static, 64)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      near_[static_cast<std::size_t>(i)] =
          body.locate_near(x_.row(i).transpose(), hinted ? (*hints)[static_cast<std::size_t>(i)] : -1);
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
    for (const auto& [a, b] : *options_.edges) {
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      if (!unchecked_[ua] && !unchecked_[ub]) continue;
      if (cleared_without_search(ua, ub)) continue;
      const Eigen::Vector3d mid = 0.5 * (x_.row(a) + x_.row(b)).transpose();
      SurfacePoint s = body_.locate_near(mid, near_[ua].face);
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
      if (s.face < 0 || s.signed_distance >= half_ - kRounding) continue;
      const Eigen::Vector3d step = (half_ - s.signed_distance) * s.normal;
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

  // The run's figures, and each vertex's closest face for the next body.
  void finish(const Eigen::MatrixX3d& start, PushOutReport& report) const {
    if (options_.closest_faces) {
      options_.closest_faces->resize(near_.size());
      for (std::size_t i = 0; i < near_.size(); ++i) (*options_.closest_faces)[i] = near_[i].face;
    }
    if (x_.rows() > 0) report.largest_move = (x_ - start).rowwise().norm().maxCoeff();
    for (std::size_t i = 0; i < near_.size(); ++i) {
      report.moved += moved_[i];
      report.still_within += near_[i].face >= 0 && near_[i].signed_distance < half_;
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
  // pass may have moved it, in any direction).
  bool cleared_without_search(std::size_t a, std::size_t b) const {
    if (near_[a].face < 0 || near_[b].face < 0) return false;
    const double sa = near_[a].signed_distance - drift_[a], sb = near_[b].signed_distance - drift_[b];
    const double half_edge = 0.5 * (x_.row(static_cast<Eigen::Index>(a)) - x_.row(static_cast<Eigen::Index>(b))).norm();
    if (std::max(sa, sb) - half_edge >= half_) return true;
    const double turn = std::acos(std::clamp(near_[a].normal.dot(near_[b].normal), -1.0, 1.0));
    return std::min(sa, sb) - kEdgeBend * half_edge * turn >= half_;
  }

  // Searched again where a vertex moved (only their closest points change),
  // from the face it was nearest before: the same answer, a shorter search.
  void search_again(const std::vector<Eigen::Index>& changed) {
    const auto count = static_cast<std::ptrdiff_t>(changed.size());
#pragma omp parallel for schedule(static, 16)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const auto i = static_cast<std::size_t>(changed[static_cast<std::size_t>(k)]);
      near_[i] = body_.locate_near(x_.row(static_cast<Eigen::Index>(i)).transpose(), near_[i].face);
      drift_[i] = 0;
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
  std::vector<Eigen::Index> stepped_, lifted_;
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
  run.finish(start, report);
  return report;
}

}  // namespace drape::geometry
