#pragma once
// One morph step under a barrier contact: the body moves to its next shape
// and the garment must never be crossed on the way.
//
// A barrier must never enter a state where the surfaces touch, so a body
// growing into the cloth cannot simply be moved and the cloth pushed out
// afterwards (what the penalty contact does). Instead each garment vertex
// near the body first moves with its closest body point (the barycentric
// blend of that face's corner displacements), fully within `carry_inner` of
// the skin and fading linearly to not at all at `carry_outer`: cloth lying on
// the skin keeps its distance while the body moves under it. The joint move of
// garment and body is then checked (Energy::max_step with the body's motion);
// where it would bring a pair too close it is cut there, the cloth is solved
// at that body with the settling Newton budget, and the rest of the move
// follows, at most `max_cuts` times.
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/physics/solver.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>

namespace drape::scene_detail {

struct BarrierMorph {
  double carry_inner = 0.005, carry_outer = 0.02;  // m
  int max_cuts = 64;
  int morph_newton = 3, settle_newton = 8;  // Newton budgets: a whole step, a step after a cut
  // Told after each partial move: the moves so far in this step and the
  // share of its way the body has made (SimulationOptions::on_partial_move).
  std::function<void(int moves, double done)> on_partial_move;
};

// A morph step the contact could not finish: how far the body got. Thrown as
// an Error; Simulation::run says why in words (the garment's girth against
// the body's there, and what in the scene makes its cloth slow to give way).
struct MorphBlocked : Error {
  MorphBlocked(const std::string& what, int step, int cuts, double done, double last_moves, bool stalled)
      : Error(what), step(step), cuts(cuts), done(done), last_moves(last_moves), stalled(stalled) {}
  int step;           // the morph step (1-based)
  int cuts;           // partial moves made
  double done;        // share of the step's move the body made
  double last_moves;  // share of the step's move the last kStallCuts partial moves made together
  bool stalled;       // stopped before max_cuts: the last kStallCuts moves made no headway
};

// A move blocked this many partial moves in a row that together took the
// body less than kStallShare of its step's way has stalled: the cloth gives
// way no more (aluminium: after the first cut each move took 1e-7 to 8e-4
// of what was left of the step, for 64 cuts and 100 s), and the step is
// given up at once.
inline constexpr int kStallCuts = 8;
inline constexpr double kStallShare = 1e-3;

// Moves `body` to `next` and the garment x (velocity v) with it; returns the
// report of the step solved at `next`. Cuts and the Newton iterations of the
// cut parts are added to `result`. Throws Error naming the step when the move
// is still blocked after max_cuts cuts, or has stalled (MorphBlocked).
StepReport barrier_morph_step(ClothSolver& solver, geometry::BodySurface& body, const Eigen::MatrixX3d& next, int step,
                              const BarrierMorph& settings, Eigen::MatrixX3d& x, Eigen::MatrixX3d& v,
                              SimulationResult& result);

}  // namespace drape::scene_detail
