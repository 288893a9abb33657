#pragma once
// A garment's self-crossings undone without knowing how they came about (a
// network's prediction has no history to roll back, unlike a simulation's
// step): the global intersection analysis of Baraff, Witkin and Kass,
// "Untangling cloth" (SIGGRAPH 2003), on the mesh's vertex graph.
//
// Where the cloth passes through itself the two sheets meet along closed
// curves. Every edge the curve crosses pierces a face of the other sheet, so
// with those edges cut the vertex graph falls apart into the piece of each
// sheet inside the curve (a patch) and the rest. A patch is on the wrong
// side of the sheet it went through: it is moved back across the faces its
// cut edges pierce, to the side the rest of its sheet is on, plus a gap. Two
// patches of one curve (the sleeve's through the side, the side's through
// the sleeve) each move half the way. Where a curve is open (it ends on the
// garment's border, so the cut separates nothing) the pierced edge and the
// face are pulled apart along the face's normal instead, half the way each.
// A crumple (an edge through a face within three rings of it: a fold
// narrower than the mesh can hold, the underarm's and the cuffs' in a heavy
// body's prediction) is neither cut nor pulled, which only hands it on from
// edge to edge: its vertices are smoothed towards their neighbours' mean.
// Rounds repeat while crossings are left, and the state with the fewest is
// returned: a pinch (two edges through each other's faces) can be handed on
// from edge to edge rather than undone, and is then left as it was.
#include <Eigen/Core>

#include <functional>
#include <memory>
#include <vector>

namespace drape::geometry {

struct UntangleOptions {
  double gap = 1e-3;            // m beyond the pierced face's plane a moved vertex gets
  int max_rounds = 4;           // searches for crossings, each followed by one set of moves
  double largest_patch = 0.25;  // share of its connected piece a patch may hold (more: the curve is not closed)
  // Rounds in a row that may leave as many crossings as the fewest seen
  // before the run gives up (a pinch it only hands on). A round that only
  // smooths crumples does not count: the fold flattens a share at a time.
  int patience = 2;
  // The garment at rest (its template: the same vertices, uncrossed), or
  // null. Given, a crossing within the crumples' reach whose edge lies
  // wholly on one side of the face there, both ends at least kLayerDepth
  // (untangle.cpp) off its plane, is two layers, not a crumple: the side is
  // known, and the edge and the face are pulled apart to it, half the way
  // each (a sleeve's two layers pinched through each other at the underarm,
  // where the seam joins them within three rings, took the crumples'
  // smoothing six rounds and more without undoing it).
  const Eigen::MatrixX3d* rest = nullptr;
  // Called after each round's moves, with `moved` flagging the vertices the
  // round moved; it may move vertices too (a push-out off the body: the
  // patches moved must not end inside it), flagging each in `moved`. The
  // crossings are then searched again where anything moved.
  std::function<void(Eigen::MatrixX3d& vertices, std::vector<char>& moved)> after_round;
};

struct UntangleReport {
  int crossings_before = 0;  // (edge, face) pairs at the start (the pairs self_edge_crossings lists)
  // Edges whose first search passed over the cloth around them: a part of
  // the garment that, seen along a coordinate axis, is a height field with a
  // simple outline, and so cannot cross itself (normal-cone culling, exact).
  int edges_culled = 0;
  int crossings_after = 0;   // left after the last round (searched again)
  int rounds = 0;            // rounds that moved something, up to the state returned
  int patches_moved = 0;     // over those rounds
  int crumples_smoothed = 0; // (edge, face) pairs smoothed as crumples over those rounds
  int layers_pulled = 0;     // (edge, face) pairs pulled to their side at rest (UntangleOptions::rest) over those rounds
  int vertices_moved = 0;    // distinct vertices moved at least once
  double largest_move = 0;   // m, over all rounds, of one vertex
};

// Moves `vertices` in place; vertices not in a crossing's patch or edge stay
// bit for bit. Faces index vertices (checked); vertices must be finite.
UntangleReport untangle(Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, const UntangleOptions& options = {});

// The same for garment after garment of one topology (a network's
// predictions): the edges, pieces and the faces' hierarchy are made once and
// the hierarchy refitted to each garment, which is most of the cost when
// nothing crosses (docs/bodies.md).
class Untangler {
 public:
  Untangler(const Eigen::MatrixX3i& faces, int num_vertices);
  ~Untangler();
  // With options.rest, a garment that crosses itself is untangled twice
  // from the same start, with the sides at rest and with the crumples'
  // smoothing only, and the result that leaves fewer crossings kept (of
  // two that leave as many, the one that moved the vertices less in sum):
  // two layers pulled to their sides can hand a crossing on where the
  // smoothing undoes it, or undo it by moving them further (docs/bodies.md).
  // Crossings still left, all of that is tried again from the same start
  // with the crumples' reach a ring wider, and kept if it leaves fewer (a
  // fold four rings wide; docs/poses.md, "The crumples' reach"): no garment
  // comes back with more crossings than the narrower reach leaves.
  UntangleReport run(Eigen::MatrixX3d& vertices, const UntangleOptions& options = {});

 private:
  // `vertices` equal to `start` on entry.
  UntangleReport run_with_reach(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& vertices, const UntangleOptions& options,
                                int crumple_rings);
  UntangleReport run_once(Eigen::MatrixX3d& vertices, const UntangleOptions& options, int crumple_rings);
  struct Topology;
  std::unique_ptr<Topology> topology_;
};

}  // namespace drape::geometry
