#pragma once
// Self contact of the garment, after IPC (Li et al. 2020, "Incremental
// Potential Contact"): the log barrier of the body barrier (energies/barrier)
// over garment-garment pairs closer than d_hat,
//
//   E(x) = kappa d_hat  sum_pairs  w_pair m_pair b(d_pair(x)^2 / d_hat^2),
//
// over two kinds of pairs: a garment vertex and a garment triangle, and two
// garment edges (the vertices alone miss two sheets crossing edge through
// edge). b is IPC's log barrier (drape/physics/barrier_function.hpp), d the
// pair's distance by its type (drape/geometry/pair_distance.hpp), m IPC's
// mollifier on edge-edge pairs (1 on point-triangle pairs), w the vertex's
// material-space area or the first edge's third of its faces' areas, so that
// kappa is a pressure (Pa), as in the body barrier.
//
// Pairs that never count:
//  - pairs sharing a vertex: their distance is 0 by construction;
//  - pairs that are neighbours in the fabric and close at rest: a vertex and
//    a triangle, or two edges, joined through at most two mesh edges whose
//    distance in the garment's rest mesh is below `rest_exclusion` d_hat. At
//    a sliver triangle or a short hem edge such a pair sits within d_hat of
//    its neighbour in the unfolded cloth, and a barrier there would only
//    fight the cloth's own shape. Pairs far apart in the fabric (a sleeve
//    against the torso) are never excluded, however close at rest.
//    With `thin_rest_neighbours` they are not left out but kept thin: each
//    pair's own d_hat is half its rest distance (at most d_hat), so it pushes
//    nothing at rest and still may not cross (a crowded armpit seam that
//    folds one triangle wide: docs/garments.md, "A user's MakeHuman top").
//    Its barrier keeps the others' scale, kappa d_hat (so it pushes harder
//    where it acts: a thin barrier that pushed as little as its width held no
//    fold, and the solver stalled on it).
//
//  - pairs inside a tangle of the rest mesh: where the garment as dressed
//    already passes through itself (geometry::self_intersections of the rest
//    mesh: the larger and the small default T-shirts do), the faces that meet
//    and one ring around them are a tangle, and a pair both of whose
//    primitives touch it is left out. A barrier cannot undo a crossing it
//    starts from (every pair of it is at a positive distance, so the energy is
//    finite and the crossing is kept); left out, the cloth's own forces may
//    pull it apart, and the rest of the garment keeps its protection.
//
// E is infinite when a pair touches, and max_step() is the continuous
// collision check (additive CCD, drape/geometry/ccd.hpp) over the same pairs:
// the largest fraction of a move along which no pair comes closer than
// min_separation of its starting distance. A solver that starts its line
// search there never lets the cloth pass through itself at an accepted state
// (outside the tangles).
//
// Pairs are found through box overlaps (geometry::overlapping_boxes), with the
// candidates kept while no vertex has moved more than a skin (a Verlet list),
// and the pairs kept for the last x, as a Newton iteration asks for value,
// gradient and Hessian at the same x.
#include <drape/energy.hpp>
#include <drape/geometry/pair_distance.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace drape::self_contact {

struct SelfContactSettings {
  double distance = 1e-3;       // d_hat, m
  double stiffness = 1e3;       // kappa, Pa
  double min_separation = 0.1;  // CCD stops a move where a pair is down to this fraction of its distance
  double rest_exclusion = 3;    // in d_hat: fabric neighbours closer than this at rest are not pairs
  bool thin_rest_neighbours = false;  // ... or are, each with half its rest distance as its d_hat
};

// A vertex and a face (a = vertex, b = face), or two edges (a < b).
enum class PairKind : unsigned char { VertexFace, EdgeEdge };

struct SelfPair {
  PairKind kind;
  int a = 0, b = 0;
  geometry::DistanceType type;
  double distance2 = 0;
  double dhat = 0;  // the pair's own d_hat (a thin rest neighbour); 0: the settings' distance
};

// The garment's primitives, fixed at bind (self_pairs.cpp).
struct SelfTopology {
  Eigen::MatrixX3i faces;
  std::vector<std::array<int, 2>> edges;   // geometry::edge_list: sorted
  Eigen::VectorXd vertex_area;             // m^2, material space
  Eigen::VectorXd edge_area;               // m^2: a third of each adjacent face's material area
  Eigen::VectorXd edge_rest2;              // m^2: squared material-space length (the mollifier's scale)
  std::vector<std::vector<int>> neighbours;  // sorted, per vertex
  std::vector<std::uint64_t> excluded;     // pair_key of the fabric neighbours close at rest, sorted
  std::vector<std::pair<std::uint64_t, double>> thin;  // or, kept thin: pair_key and own d_hat, sorted
  std::vector<char> tangled;               // per vertex: in a tangle of the rest mesh (or a ring around one)
  int tangled_faces = 0;                   // faces of the rest mesh that meet another (self_intersections)
  int vertices = 0;

  // The pair's 4 vertices: the vertex then the face's corners, or both edges' ends.
  std::array<int, 4> vertices_of(PairKind kind, int a, int b) const;
  // True for a pair that never counts: sharing a vertex, both primitives in a
  // tangle, or in `excluded`.
  bool skipped(PairKind kind, int a, int b) const;
  // The pair's own d_hat when it is a thin rest neighbour, else 0.
  double thin_dhat(PairKind kind, int a, int b) const;
};

std::uint64_t pair_key(PairKind kind, int a, int b);

class SelfContact final : public Energy {
 public:
  explicit SelfContact(const SelfContactSettings& settings);
  ~SelfContact() override;

  // Needs context.garment (with material-space UVs); no body.
  void bind(const EnergyContext& context) override;
  bool bounds_steps() const override { return true; }
  // 0: the reach of this energy is cloth to cloth, and `drape optimize` reads
  // activation_distance as the gap to grow a body up to (energy.hpp).
  double activation_distance() const override { return 0; }
  double value(const Eigen::MatrixX3d& x) const override;
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override;
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  // The body's motion is ignored: only the cloth meets itself.
  double max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from = nullptr,
                  const Eigen::MatrixX3d* body_to = nullptr) const override;

 private:
  void check(const Eigen::MatrixX3d& x) const;
  std::shared_ptr<const std::vector<SelfPair>> cached_pairs(const Eigen::MatrixX3d& x) const;
  // The pair's energy over the scalar S: double for the value, Dual<12, order> for its derivatives.
  template <class S>
  S pair_energy(const SelfPair& pair, const std::array<Vec3<S>, 4>& q) const;
  template <class D>
  D pair_dual(const SelfPair& pair, const Eigen::MatrixX3d& x) const;
  void hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const;

  // How far the cloth may move before the candidates are found again (their
  // boxes are grown by d_hat / 2 and this).
  double candidate_skin() const { return settings_.distance; }
  // The candidates when a move from x by dx stays within their reach (every
  // pair whose swept boxes overlap is one of them), else none.
  std::optional<std::vector<SelfPair>> candidates_covering(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx) const;

  SelfContactSettings settings_;
  std::unique_ptr<SelfTopology> topology_;

  struct Cache {
    std::mutex mutex;  // energies may be evaluated from several threads (graph loss nodes)
    Eigen::MatrixX3d x;
    std::shared_ptr<const std::vector<SelfPair>> pairs;
    // The broad phase's candidates, found at candidates_x with the boxes grown by a skin.
    Eigen::MatrixX3d candidates_x;
    std::vector<SelfPair> candidates;
  };
  mutable Cache cache_;
};

}  // namespace drape::self_contact
