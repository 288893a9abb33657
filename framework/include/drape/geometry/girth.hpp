#pragma once
// A tape measure around a mesh: the girth of its horizontal cross-section at
// a height (Y up), as a tailor measures a chest. The plane y = height cuts the
// mesh's faces into segments; they are chained into loops, and the loop that
// encloses the vertical line through `centre` (x, z) is the one measured
// (the torso, not an arm beside it). A tape spans the hollows between
// ribs or folds, so the girth of a closed body is the perimeter of the
// loop's convex hull; the loop's own length is what a garment's fabric
// spans, and is given too.
#include <Eigen/Core>

namespace drape::geometry {

struct Girth {
  bool found = false;     // a loop encloses the centre line
  double tape = 0.0;      // m: perimeter of the loop's convex hull
  double length = 0.0;    // m: the loop's own length
  int loops = 0;          // closed loops the plane cut (arms, legs, ...)
  double longest_loop = 0.0;  // m: the longest closed loop's own length, whether it encloses the centre or not
  // m: the loop's length in the mesh's material space (the cloth at rest:
  // what the loop measures unstretched), when a material space is given;
  // else 0. A garment crumpled in 3D keeps its material length, one whose
  // pattern is cut small has a short one.
  double material_length = 0.0;
};

// Faces lying in the plane or touching it at a single vertex add nothing; the
// height is nudged by 1e-9 m off any vertex so that every cut is a clean one.
// With `uv` and `uv_faces` (a material coordinate per corner, in metres, as
// a garment's Mesh has them), the loop's material_length is measured too.
Girth horizontal_girth(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, double height,
                       const Eigen::Vector2d& centre, const Eigen::MatrixX2d* uv = nullptr,
                       const Eigen::MatrixX3i* uv_faces = nullptr);

// Height of a body's crotch above its soles (m): the lowest horizontal cut,
// going up from a quarter of the height, whose loop goes around the body's
// vertical centre line (below it, the cut passes between the legs). NaN
// when none does.
double crotch_height(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
