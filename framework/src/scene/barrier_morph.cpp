// One morph step under a barrier contact (barrier_morph.hpp).
#include "barrier_morph.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace drape::scene_detail {

namespace {

// x moved with the body from its current vertices to `next` (see the header).
Eigen::MatrixX3d carried_with_body(const Eigen::MatrixX3d& x, const geometry::BodySurface& body,
                                   const Eigen::MatrixX3d& next, double inner, double outer) {
  const std::vector<geometry::SurfacePoint> hits = body.locate_all(x, outer);
  const Eigen::MatrixX3d& from = body.vertices();
  const Eigen::MatrixX3i& faces = body.faces();
  Eigen::MatrixX3d carried = x;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const geometry::SurfacePoint& hit = hits[static_cast<std::size_t>(v)];
    if (hit.face < 0) continue;
    const double d = std::abs(hit.signed_distance);
    const double weight = d <= inner ? 1.0 : std::max(0.0, (outer - d) / (outer - inner));
    Eigen::RowVector3d move = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int c = faces(hit.face, k);
      move += hit.barycentric[k] * (next.row(c) - from.row(c));
    }
    carried.row(v) += weight * move;
  }
  return carried;
}

}  // namespace

StepReport barrier_morph_step(ClothSolver& solver, geometry::BodySurface& body, const Eigen::MatrixX3d& next, int step,
                              const BarrierMorph& settings, Eigen::MatrixX3d& x, Eigen::MatrixX3d& v,
                              SimulationResult& result) {
  double left = 1.0;                // share of the step's move still to make
  std::vector<double> headway;      // share of the whole step each partial move made
  for (int cuts = 0;; ++cuts) {
    const Eigen::MatrixX3d from = body.vertices();
    const Eigen::MatrixX3d carried = carried_with_body(x, body, next, settings.carry_inner, settings.carry_outer);
    const double alpha = solver.max_step(x, carried - x, &from, &next);
    if (alpha >= 1) {
      x = carried;
      body.update(next);
      return solver.step(x, v);
    }
    constexpr auto window = static_cast<std::size_t>(kStallCuts);
    double recent = 0.0;
    for (std::size_t k = headway.size() >= window ? headway.size() - window : 0; k < headway.size(); ++k) recent += headway[k];
    const bool stalled = headway.size() >= window && recent < kStallShare;
    if (cuts >= settings.max_cuts || stalled)
      throw MorphBlocked("simulate: the body grows into the garment faster than the contact can push it away (morph step " +
                             std::to_string(step) + " still blocked after " + std::to_string(cuts) + " partial moves)",
                         step, cuts, 1.0 - left, recent, stalled);
    ++result.morph_substeps;
    headway.push_back(alpha * left);
    left *= 1.0 - alpha;
    x += alpha * (carried - x);
    body.update(from + alpha * (next - from));
    // The cut left a pair close: the cloth gets the settling budget to move
    // away before the rest of the move.
    solver.set_max_newton_iterations(settings.settle_newton);
    const StepReport r = solver.step(x, v);
    solver.set_max_newton_iterations(settings.morph_newton);
    result.iterations += r.iterations;
    result.line_search_failures += r.line_search_failures;
    if (settings.on_partial_move) settings.on_partial_move(cuts + 1, 1.0 - left);
  }
}

}  // namespace drape::scene_detail
