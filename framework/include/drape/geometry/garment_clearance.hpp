#pragma once
// A predicted garment cleared of the body and of itself, garment after
// garment of one topology: the push-out (push_out.hpp: vertices, edges and
// faces off the body) and then the untangle (untangle.hpp: the garment's
// crossings of itself undone), each untangle round's moves pushed off the
// body again. One implementation for the models' `push_out` node and for
// `drape predict --push-out`, which did the same steps with code of its own
// (and a whole push-out after every round where the node pushes out only
// what the round moved).
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/push_out.hpp>
#include <drape/geometry/untangle.hpp>

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace drape::geometry {

struct GarmentClearanceOptions {
  double margin = kPushOutMargin;  // m: the push-out's clearance off the body
  // The edges lifted and the faces kept off the body's peaks (push_out.hpp);
  // false: the vertices only.
  bool lift_edges = true;
  // The crossings of itself undone after the push-out; false: not.
  bool untangle = true;
  // The cloth's thickness in the shipped scenes' self-contact: the gap an
  // untangled patch is given beyond the cloth it went through.
  double self_gap = 1e-3;
  // Untangle rounds at most, each followed by the push-out of what it moved
  // (an open curve at a sleeve's cuff took three on the human rig's heavy
  // test bodies, a closed one one: docs/bodies.md).
  int untangle_rounds = 6;
};

class GarmentClearance {
 public:
  // faces: the garment's (indices checked by push_out and the untangle).
  GarmentClearance(const Eigen::MatrixX3i& faces, int num_vertices, const GarmentClearanceOptions& options = {});

  // The whole push-out of `vertices` off `body`, each search starting from
  // the face the last garment's search of that vertex ended on (the same
  // result, a shorter search).
  PushOutReport push_out(const BodySurface& body, Eigen::MatrixX3d& vertices);

  // The push-out again on the vertices flagged in `moved` and their
  // neighbours only (with the edges among them): the rest did not move
  // since the whole push-out cleared them, and a few dozen searches cost a
  // hundredth of a whole push-out. Those this moves are flagged too. Call
  // after push_out() on the same body.
  void push_out_moved(const BodySurface& body, Eigen::MatrixX3d& vertices, std::vector<char>& moved);

  // The garment's crossings of itself undone (options.untangle), each
  // round's moves pushed off `body` again (push_out_moved). rest: the
  // garment at rest, where two layers pinched through each other belong
  // (UntangleOptions::rest), or null. Call after push_out() on the same body.
  UntangleReport untangle(const BodySurface& body, Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d* rest);

  // push_out() then untangle(), the reports of both.
  struct Report {
    PushOutReport pushed;
    UntangleReport untangled;
  };
  Report run(const BodySurface& body, Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d* rest);

  const std::vector<std::array<int, 2>>& edges() const { return edges_; }
  const VertexAdjacency& adjacency() const { return adjacency_; }
  const GarmentClearanceOptions& options() const { return options_; }

 private:
  PushOutOptions push_out_options(std::vector<int>* closest_faces, const std::vector<std::array<int, 2>>* edges) const;

  GarmentClearanceOptions options_;
  Eigen::MatrixX3i faces_;
  std::vector<std::array<int, 2>> edges_;
  VertexAdjacency adjacency_;
  std::optional<Untangler> untangler_;  // when options_.untangle
  std::vector<int> closest_faces_;      // the last garment's closest face of each vertex
};

}  // namespace drape::geometry
