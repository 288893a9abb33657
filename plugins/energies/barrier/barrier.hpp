#pragma once
// Barrier contact between the garment and the body, after IPC (Li et al.
// 2020, "Incremental Potential Contact"): a log barrier on every primitive
// pair closer than the activation distance d_hat,
//
//   E(x) = kappa d_hat  sum_pairs  w_pair m_pair b(d_pair(x)^2 / d_hat^2),
//
// over three kinds of pairs: a garment vertex and a body triangle, a body
// vertex and a garment triangle, a garment edge and a body edge (vertices
// alone are not enough: the body is finer than the cloth, so its edges and
// vertices poke through cloth triangles whose corners are all outside).
// b is the log barrier (drape/physics/barrier_function.hpp), d the pair's distance by its
// distance type (drape/geometry/pair_distance.hpp), m IPC's mollifier on edge-edge pairs (1
// for the others), w an area that makes kappa a pressure: the garment
// vertex's material-space area, the body vertex's area, or the garment
// edge's third of its faces' areas. Units: kappa in Pa, d_hat in m, E in J;
// the push of a pair at distance d is kappa w |b'(r)| 2 d / d_hat (N), about
// 0.2 kappa at d = 0.9 d_hat, 4.3 kappa at d_hat / 2, rising without bound.
//
// E is infinite when a pair touches, and max_step() is the continuous
// collision check: the largest fraction of a move (of the garment, and of the
// body when it morphs) along which no pair comes closer than a tenth of its
// starting distance (additive CCD, drape/geometry/ccd.hpp). A solver that
// starts its line search there keeps the two surfaces apart at every accepted
// state, by construction. Only the garment's vertices are variables; the body
// is prescribed (it moves between solves, through max_step's body motion).
//
// The body must be a geometry::BodySurface and outlive the energy. Pairs are
// found through box overlaps (geometry::overlapping_boxes) and kept for the
// last x and body revision, as a Newton iteration asks for value, gradient and
// Hessian at the same x.
#include <drape/geometry/pair_distance.hpp>

#include <drape/dual.hpp>
#include <drape/energy.hpp>
#include <drape/physics/dissipation.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace drape::barrier {

struct BarrierSettings {
  double distance = 1e-3;     // d_hat, m
  double stiffness = 1e3;     // kappa, Pa
  double min_separation = 0.1;  // CCD stops a move where a pair is down to this fraction of its distance
  double friction = 0;        // mu, Coulomb's coefficient between cloth and body (0: frictionless)
  // eps_v, m/s: slower slip is held as static friction (IPC's smoothing). IPC's
  // dynamics use 1 mm/s; a drape is quasi-static, and at 1 mm/s a fifth of
  // the coarse drapes still crept when their steps ran out (docs/scenes.md).
  double slip_velocity = 1e-2;
};

enum class PairKind : unsigned char { GarmentVertexBodyFace, BodyVertexGarmentFace, GarmentEdgeBodyEdge };

struct ContactPair {
  PairKind kind;
  int garment = 0;  // garment vertex, face or edge
  int body = 0;     // body face, vertex or edge
  geometry::DistanceType type;
  double distance2 = 0;
};

class BarrierContact final : public Energy {
 public:
  struct Topology;   // the garment's and body's primitives, fixed at bind (barrier_state.hpp)
  struct BodyState;  // what depends on the body's current positions (barrier_state.hpp)

  explicit BarrierContact(const BarrierSettings& settings);
  ~BarrierContact() override;

  // Needs context.garment (with material-space UVs) and context.body, a BodySurface.
  void bind(const EnergyContext& context) override;
  bool needs_body() const override { return true; }
  bool bounds_steps() const override { return true; }
  double activation_distance() const override { return settings_.distance; }
  double value(const Eigen::MatrixX3d& x) const override;
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override;
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  double max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from = nullptr,
                  const Eigen::MatrixX3d* body_to = nullptr) const override;

  // Friction (friction.cpp), with settings.friction > 0: IPC's lagged
  // friction over the same pairs. Each pair within d_hat at a step's start is
  // a contact with a normal force lambda (the barrier's push there), a tangent
  // plane T and the closest points' weights on the garment side, all fixed for
  // the step; the body stands still while a step is solved (a morph moves
  // the cloth near the body with it first, scene/barrier_morph.cpp), so the
  // slip u = T^T (garment point's move since the step's start), and
  //
  //   D(x) = sum_contacts mu lambda f0(|u|),   f0(y) = y for y >= eps,
  //          -y^3 / (3 eps^2) + y^2 / eps + eps / 3 below (eps = eps_v h):
  //
  // kinetic friction mu lambda against any slip faster than eps_v, and a
  // stiff, smooth stand-in for static friction below it. D's Hessian is
  // positive semidefinite as written (no projection).
  // That friction as its own potential (Friction, friction.cpp); null without friction.
  Dissipation* dissipation() override;

  // The pairs within d_hat at some x, with the body state they were found on.
  struct PairSet {
    std::shared_ptr<const BodyState> body;
    std::vector<ContactPair> pairs;
  };

 private:
  void check(const Eigen::MatrixX3d& x) const;
  // The body state of the current body revision (rebuilt when it moved); caller holds the mutex.
  std::shared_ptr<const BodyState> body_state_locked() const;
  std::shared_ptr<const BodyState> body_state() const;
  std::shared_ptr<const PairSet> cached_pairs(const Eigen::MatrixX3d& x) const;
  // How far the garment may move before the Verlet list of candidates is
  // found again (its boxes are grown by d_hat and this): the line search's
  // trials and the next iterations mostly move less.
  double candidate_skin() const { return settings_.distance; }
  // The pair's 4 points: garment and body vertices as its kind orders them.
  std::array<Eigen::Vector3d, 4> pair_points(const ContactPair& pair, const Eigen::MatrixX3d& x) const;
  // The pair's garment vertices (its variables), and how many.
  int pair_vertices(const ContactPair& pair, std::array<int, 3>& vertex) const;
  // The pair's energy over the scalar S: double for the value, Dual<3 K, order>
  // for its derivatives over its K garment vertices.
  template <class S>
  S pair_energy(const ContactPair& pair, const BodyState& body, const std::array<Vec3<S>, 4>& q) const;
  // D: Dual<3 K, 1> for the gradient, Dual<3 K, 2> for the Hessian too.
  template <class D>
  D pair_dual(const ContactPair& pair, const BodyState& body, const Eigen::MatrixX3d& x) const;
  void hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const;

  // A pair's contact at x: its garment vertices and their weights in the
  // pair's garment point, the unit normal from the body's closest point to
  // the garment's, and the barrier's push along it (N).
  struct Contact {
    std::array<int, 3> vertex{};
    std::array<double, 3> weight{};
    int count = 0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double normal_force = 0;
  };
  Contact contact(const ContactPair& pair, const BodyState& body, const Eigen::MatrixX3d& x) const;
  // The area that weights a pair's energy and its friction: the garment
  // vertex's, the body vertex's, or the garment edge's third of its faces'.
  double pair_area(const ContactPair& pair, const BodyState& body) const;
  // The friction over this barrier's pairs (friction.cpp): a nested class,
  // so it reads the pairs, contacts and settings without widening the
  // barrier's interface.
  class Friction;

  BarrierSettings settings_;
  std::unique_ptr<Friction> friction_;  // with settings.friction > 0
  const geometry::BodySurface* body_ = nullptr;
  std::unique_ptr<Topology> topology_;

  struct Cache {
    std::mutex mutex;  // energies may be evaluated from several threads (graph loss nodes)
    std::shared_ptr<const BodyState> body;
    Eigen::MatrixX3d x;
    std::shared_ptr<const PairSet> pairs;
    // The broad phase's candidates, found at candidates_x on candidates_body
    // with the boxes grown by a skin (cached_pairs).
    std::shared_ptr<const BodyState> candidates_body;
    Eigen::MatrixX3d candidates_x;
    std::vector<ContactPair> candidates;
  };
  mutable Cache cache_;
};

}  // namespace drape::barrier
