#pragma once
// Dressing a garment on a specific body.
//
// The split: a garment template (plugin kind "garment") builds its mesh placed
// around a *canonical* torso described by a few numbers (half-width, depth,
// neck height, arm angle; defaults measured from the mean parametric body), so
// templates never depend on a body plugin. dress() then fits that placement to
// an actual body mesh: it pushes every vertex that lies inside the body or
// closer than `margin` to it out along the body normal, and spreads the
// correction over the neighbouring vertices so the surface stays smooth; if
// that folded the cloth through itself, it smooths and pushes again until it
// does not (DressOptions::untangle_rounds). The material space (UVs) is
// untouched: only the 3D rest/start state changes.
#include <drape/energy.hpp>
#include <drape/garment_layers.hpp>
#include <drape/mesh.hpp>

#include <string>
#include <vector>

namespace drape {

struct DressOptions {
  double margin = 0.01;     // m: wanted clearance between garment vertices and body
  int max_iterations = 30;  // push + smooth rounds
  int smoothing_steps = 3;  // displacement-averaging steps per round
  bool lay_pieces = true;   // a garment of several pieces: each laid outside the one under it (garment_layers.hpp)
  // When the pushed garment passes through itself (neighbours pushed onto
  // both sides of a crease; geometry::self_edge_crossings): up to this many
  // rounds that smooth every displacement and push again, keeping the least
  // tangled (0: none).
  int untangle_rounds = 20;
};

struct DressReport {
  int inside_before = 0;          // vertices inside the body before dressing
  int pushed = 0;                 // vertices moved at least once
  int iterations = 0;
  double deepest_before = 0;      // m, largest penetration before dressing (>= 0)
  double min_distance_after = 0;  // m, smallest signed distance after dressing
  LayerReport layers;             // a garment of several pieces: how they were laid in layers (garment_layers.hpp)
  // Edges through faces of the garment (geometry::self_edge_crossings,
  // touching included) after the pushes, and in the result; the untangling
  // round kept (0: the pushes' result).
  int tangled_before = 0, tangled_after = 0, untangle_rounds = 0;
  // Vertices that started deeper inside the body than kThroughDepth with
  // their cloth facing away from the way they were pushed out (the garment's
  // outward normal against the body's at their closest point): a panel
  // placed through the body, pushed out of its far side. A shirt modelled
  // 15 cm forward of the body otherwise went on as an apron, its back panel
  // pushed out through the chest, and "settled" in front of the body. The
  // start positions' indices; deepest_through their largest depth (m).
  std::vector<int> pushed_through;
  double deepest_through = 0;
};

// How deep a vertex facing the wrong way must start for dressing to count
// it as pushed through the body, and how many such vertices mean the
// garment was placed through it (placed_through). Measured (garment_dressing.cpp):
// every shipped scene's garment and size, and the coarse shirt graded for
// BMI 10-65 bodies, has none deeper than 2.4 cm; the coarse shirt moved 8 cm
// or more forward, back or aside has 1-126 beyond 4 cm.
inline constexpr double kThroughDepth = 0.035;
inline constexpr int kThroughCount = 3;

// Whether dressing found the garment placed through the body (kThroughCount or more pushed_through).
inline bool placed_through(const DressReport& report) {
  return static_cast<int>(report.pushed_through.size()) >= kThroughCount;
}

// A garment is modelled around the body it is dressed on (a template's
// canonical torso, a mesh file around the body model's mean shape). One that
// is far larger than the body, or lies apart from it, is in other units or
// placed elsewhere: dressing and draping it would run for minutes and hand
// back nonsense (a shirt in centimetres, 120 m tall, "settles" nowhere).
// Throws ConfigError naming `what` (e.g. "garment 'mesh' (shirt.obj)"), the
// sizes, and the likely scale. Checked by Simulation and the assets build.
// Also one turned about the vertical: where both the garment and the body
// are clearly wider one way than the other across (the body: its shoulders
// and arms along x; a shirt: its sleeves), their widest ways more than 45
// degrees apart (a shirt exported turned 90 degrees otherwise began with
// 35 of its edges through the body, refused as "crossing" without a cause).
// A garment round across (a skirt, a tube) is not checked for it.
void check_garment_around_body(const Mesh& garment, const Mesh& body, const std::string& what);

// Fits `garment.mesh.vertices` to the body; `body` answers closest-point queries.
DressReport dress(Garment& garment, const BodyQuery& body, const DressOptions& options = {});

// The same against a closed, outward-oriented body mesh (a geometry::BodySurface).
DressReport dress(Garment& garment, const Mesh& body, const DressOptions& options = {});

}  // namespace drape
