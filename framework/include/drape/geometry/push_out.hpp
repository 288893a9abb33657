#pragma once
// A predicted garment's vertices moved out of the body: each vertex nearer the
// body than `margin` (or inside it) is moved along the signed distance's
// gradient (the outward normal at its closest body point) to `margin` outside,
// and the search repeated, since a move can change which part of the body is
// closest (a vertex in a crease); the rest stay where they are. The
// post-processing TailorNet applies (the seed's Table 6.6, "-post"), for a
// network's prediction, never for a simulated drape. It clears the vertices
// only: an edge between two moved vertices can still pass through a thin
// part of the body (the crossings metric counts those).
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

struct PushOutReport {
  int moved = 0;             // vertices moved at least once
  double largest_move = 0;   // m
  int passes = 0;            // searches run (at most max_passes)
  int still_within = 0;      // vertices still nearer than margin / 2 after the last pass
  int edges_lifted = 0;      // edge lifts (an edge lifted in two passes counts twice)
  int edges_searched = 0;    // edge midpoints searched, over all passes
  int beyond_reach = 0;      // with edges: vertices found outside and beyond their reach, never searched in full
  int edges_tested_whole = 0;  // with edges: edges tested against the body's faces end to end (lifted, near it, or not kept out by its ends' distances)
  int fins_cleared = 0;      // with edges: edges moved off a thin fold of the body they passed through (push_out.cpp)
  int peaks_cleared = 0;     // with faces: faces lifted off a body vertex that rose through them (push_out.cpp)
};

// The clearance drape eval --push-out and drape predict --push-out give: about
// the barrier's activation distance, where the simulated cloth rests.
inline constexpr double kPushOutMargin = 1e-3;

struct PushOutOptions {
  double margin = kPushOutMargin;
  int max_passes = 4;
  // As closest_faces below.
  std::vector<int>* closest_faces = nullptr;
  // The garment's edges (geometry::edge_list of its faces). Given, each pass also lifts every
  // edge whose midpoint lies nearer the body than margin / 2 (both its ends
  // moved along the body's normal at the midpoint until it is margin / 2
  // out): two vertices outside do not keep the body's ridges (a shoulder
  // blade, a hip, a bent elbow) from poking through the edge between them.
  // Only edges the signed distance's Lipschitz bound cannot clear are
  // searched (max of the ends' distances - half the edge < margin / 2), and
  // of those only edges whose nearer end, less twice the sagitta of the arc
  // the body's normal turns through between the ends' closest points, is
  // within margin / 2 (a ridge sharper than those normals show is missed
  // there). An edge whose midpoint is within 0.6 margin has its quarter
  // points searched too, and is lifted by the lowest of the three (a ridge
  // can cross an edge off its middle). The last pass moves vertices only, so
  // every vertex keeps the margin's promise. After the passes every edge its
  // ends' distances cannot keep off the body (their sum below its length) is
  // tested end to end, exactly, and one that crosses the body is moved off
  // it with the lifted and near edges (push_out.cpp, clear_fins); an edge is
  // left crossing only where that move fails (the crossed faces' normals
  // cancel, or kFinSteps margins do not clear it).
  const std::vector<std::array<int, 2>>* edges = nullptr;
  // The garment's faces. Given (with edges), a face whose vertices and edges
  // are clear but which a peak of the body rises through (the tip of a part
  // the body's mesh draws with long edges: a heavy woman's breast on the
  // human rig, its edges 3.4-4.5 cm) is lifted until the peak is margin / 2
  // below it; the peak is found by climbing the body's vertices from the
  // closest points of the face's corners (push_out.cpp, clear_peaks).
  const Eigen::MatrixX3i* faces = nullptr;
  // With edges, each vertex's first search stops at its reach (the margin, or
  // half its longest edge plus half the margin): beyond it a vertex is
  // neither moved nor needed by an edge's bound, and its side comes from its
  // neighbours (push_out.cpp). The result is the same bits either way; false
  // searches every vertex in full (to check that).
  bool cut_at_reach = true;
};

// Moves `vertices` in place. margin >= 0, max_passes >= 1.
// closest_faces (optional): in, a face near each vertex's closest point (the
// last body's answer, for a garment pushed out of body after body of one
// topology; -1 or a wrong size: none), where each search starts; out, the
// faces of this body. The result is the same with or without them (the
// searches return the same closest point); the search is shorter.
PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices, double margin = kPushOutMargin,
                       int max_passes = 4, std::vector<int>* closest_faces = nullptr);
PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices, const PushOutOptions& options);

}  // namespace drape::geometry
