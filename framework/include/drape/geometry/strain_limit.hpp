#pragma once
// Strain limiting (Provot 1995): every edge longer than (1 + limit) times its
// rest length is shortened to that length, its two ends moved towards each
// other by half the excess each, edge after edge in order (Gauss-Seidel),
// sweep after sweep over the edges that share a vertex a sweep moved, until
// none is too long or the sweeps run out. A garment predicted by skinning
// stretches the cloth where the skinning does (a raised arm's underarm: on
// the posed model's test bodies a median 4.5 edges a body beyond the
// simulation's own most strained edge, the worst at twice its rest length);
// cloth does not, and a simulator with strain limits (ArcSim) never lets it.
// Nothing else moves: edges shorter than the limit are left as they are.
#include <drape/mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

struct StrainLimitReport {
  int sweeps = 0;          // sweeps run (1 when nothing was too long)
  int shortened = 0;       // edge shortenings, over all sweeps
  double worst_before = 0; // the largest l / rest - 1 before
  double worst_after = 0;  // and after (above the limit only when the sweeps ran out)
};

// Moves `x` in place. edges: unique vertex pairs; rest: one length per edge
// (> 0); limit >= 0 (a fraction: 0.5 lets an edge stretch to 1.5 times its
// rest); max_sweeps >= 1. With slack > 0 only edges beyond (1 + limit +
// slack) times their rest are shortened (still to 1 + limit): the chain of
// shortenings a long edge starts along its neighbours stops sooner (Provot's
// sweeps converge slowly: 29-47 sweeps of 276-460 shortenings on a heavy
// posed body without it). moved (optional, one flag per vertex): set for
// each vertex it moves, left alone for the rest. Error on a size mismatch, a
// rest length <= 0 or a negative slack.
StrainLimitReport limit_strain(Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges,
                               const std::vector<double>& rest, double limit, int max_sweeps = 50, double slack = 0.0,
                               std::vector<char>* moved = nullptr);

// The largest l / rest - 1 over the edges (-1 with none).
double worst_strain(const Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges, const std::vector<double>& rest);

// The material-space (UV) rest length of each edge of `edges` (sorted, as
// edge_list gives them) in `mesh`: the
// mean of the lengths of its sides in the faces that hold it (an edge on a UV
// seam has one side in each panel, the same length where the seam is sewn
// edge to edge). ConfigError without UVs, Error for an edge no face holds.
std::vector<double> material_edge_lengths(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges);

}  // namespace drape::geometry
