#pragma once
// Body collision energy: a one-sided cubic penalty that keeps every garment
// vertex at least `margin` outside the body (the seed's collision loss, after
// PBNS, Bertiche et al. 2021, and SNUG, Santesteban et al. 2022):
//
//   E(x) = sum_v a_v k phi(margin - d_v(x))        phi(delta) = max(0, delta)^3 / 3
//
// d_v is the signed distance of vertex v to the body (negative inside), equal
// to n^T (x_v - p) with p the closest body point and n its outward unit normal;
// a_v the vertex's lumped material-space area (geometry::vertex_areas), so the
// energy is resolution independent; k the stiffness in N/m^4. Units: E in J,
// the force on vertex v is a_v k delta^2 n (N), i.e. a contact pressure
// k delta^2 (Pa) with delta = margin - d the penetration into the margin.
//
// Derivatives (c = a_v k, delta = margin - d, with phi', phi'' from penalty.hpp):
//   gradient  -c phi'(delta) n
//   Hessian    c phi''(delta) n n^T - c phi'(delta) D
// where D is the Hessian of the signed distance: zero when the closest point is
// inside a face (then the energy is that of the face's tangent plane and the
// first term is all), (I - n n^T)/d near a body vertex, (I - n n^T - t t^T)/d
// near an edge of direction t. D's eigenvectors are n (eigenvalue 0) and the
// tangents, so the nearest PSD block (project_psd) keeps the first term
// (phi'' >= 0) and keeps -c phi' D only where it is PSD: inside the body (d < 0),
// at concave edges and vertices. Outside near a convex edge it is dropped,
// which leaves the tangent-plane Hessian 2 c delta n n^T.
//
// Defaults (see plugin.cpp for the numbers): a T-shirt in tension T ~ 3 N/m
// around a torso of radius R ~ 0.1 m presses on it with T / R ~ 30 Pa; with
// k = 1e7 N/m^4 that balances at delta = 1.7 mm, inside the 3 mm margin (the
// cloth stays 1.3 mm off the skin), and the ~100 Pa under the shoulders, which
// carry the shirt's weight, at delta = 3.2 mm, 0.2 mm into the body. The margin
// is measured from the cloth's mid-surface; half of a knit's thickness (0.24 mm)
// is well inside it and is not added separately.
//
// Deep vertices: d_v measures to the *nearest* side of the body. A vertex that
// starts inside a part thicker than twice its depth (a garment predicted 4 cm
// into the torso) is pushed straight out. A vertex past the medial axis of a
// thin part (deeper than half the arm's thickness) is nearer the far side and is
// pushed out there, dragging the cloth through; no stateless energy can tell
// which side it came from. `max_depth` (off by default, like the seed's loss)
// bounds the harm: beyond it the penalty grows linearly, so the push no longer
// grows with depth and a stray vertex is held by its neighbours' elasticity,
// while every vertex deeper than max_depth is still pushed out with the
// pressure it would have at max_depth.
//
// The body must outlive the energy. A Newton iteration asks for the value, the
// gradient and the Hessian at the same x (and the line search's accepted trial
// is the next gradient's x), so the contacts of the last x are kept and
// reused while x and the body (BodySurface::revision, bumped by every morph
// update) are unchanged: one closest-point pass per iteration instead of three.
#include "contacts.hpp"
#include "penalty.hpp"

#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace drape::collision {

struct CollisionSettings {
  double stiffness = 1e7;  // N/m^4
  double margin = 3e-3;    // m
  double max_depth = 0;    // m; 0: no cap (pure cubic)
  // m: R of the smooth distance (smooth_distance.hpp) over the body's vertices
  // within R; 0: the exact closest-point distance. Must exceed the margin.
  double smoothing = 0;
  // Push off the far side of a concave crease too (crease_penalty.hpp), when
  // the body is a BodySurface and the distance is exact (smoothing 0).
  bool creases = true;
};

class BodyCollision final : public Energy {
 public:
  explicit BodyCollision(const CollisionSettings& settings);

  // Needs context.garment (with material-space UVs) and context.body.
  void bind(const EnergyContext& context) override;
  bool needs_body() const override { return true; }
  double value(const Eigen::MatrixX3d& x) const override;
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override;
  // Sparsity contract: appends exactly one 3x3 block (9 triplets) on the
  // diagonal for *every* garment vertex, in vertex order, zeros where the vertex
  // is outside the margin. The pattern of the summed Hessian then does not
  // change when vertices enter or leave contact, so the solver can keep its
  // symbolic factorisation across iterations.
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  // The same blocks' lower triangles: 6 triplets for every vertex, in vertex order.
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  // The exact distance has kinks; the smooth one (smoothing > 0) is C2.
  bool has_kinks() const override { return !(settings_.smoothing > 0); }
  // The exact distance's push at the six points `radius` away from the vertex.
  void vertex_gradient_samples(const Eigen::MatrixX3d& x, int vertex, double radius,
                               std::vector<Eigen::Vector3d>& samples) const override;

 private:
  void check(const Eigen::MatrixX3d& x) const;
  // The exact contacts, or the smooth ones when settings_.smoothing > 0, with distance Hessians.
  std::vector<Contact> contacts(const Eigen::MatrixX3d& x) const;
  // The exact closest-point contacts; vertices provably beyond the margin are skipped (see the .cpp).
  std::vector<Contact> exact_contacts(const Eigen::MatrixX3d& x) const;
  // The contacts of x, from the cache when x and the body are unchanged.
  std::shared_ptr<const std::vector<Contact>> cached_contacts(const Eigen::MatrixX3d& x) const;
  // Every vertex's block in vertex order: all 9 entries, or the 6 of its lower triangle.
  void hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const;
  // Vertex v's 3 x 3 Hessian block at its contact (zero outside the margin).
  Eigen::Matrix3d vertex_hessian(Eigen::Index v, const Contact& contact, bool project_psd) const;
  // The far-side terms of the contacts of the searched vertices within the margin (crease_penalty.hpp).
  void add_crease_terms(const Eigen::MatrixX3d& x, const std::vector<Eigen::Index>& searched,
                        std::vector<Contact>& contacts) const;
  // Vertex v's far-side terms at p, whose nearest body point is `contact`'s:
  // the far wall outside the near face's normal group, and the faces across
  // the near face's edges (the two ramps of crease_penalty.hpp).
  CreaseTerm crease_at(const Eigen::Vector3d& p, const Contact& contact, Eigen::Index v) const;
  // The gradient of vertex v's penalty at penetration delta (> 0) into the margin along `normal`.
  Eigen::Vector3d push_gradient(Eigen::Index v, double delta, const Eigen::Vector3d& normal) const;

  CollisionSettings settings_;
  CubicPenalty penalty_;
  const BodyQuery* body_ = nullptr;
  Eigen::VectorXd area_;  // lumped material-space area per vertex, m^2
  const geometry::BodySurface* surface_ = nullptr;  // the body when it can tell its revision (cache on)
  // Per body face, its normal group (normal_groups.hpp); empty: creases off, smoothing on, or no BodySurface.
  std::vector<int> face_group_;

  struct Cache {
    std::mutex mutex;  // energies may be evaluated from several threads (graph loss nodes)
    Eigen::MatrixX3d x;
    std::uint64_t revision = 0;
    std::shared_ptr<const std::vector<Contact>> contacts;
    // Per vertex, where it was and its signed distance at its last exact
    // query (on body revision `reference_revision`).
    Eigen::MatrixX3d reference;
    Eigen::VectorXd reference_distance;
    std::uint64_t reference_revision = 0;
  };
  mutable Cache cache_;
};

}  // namespace drape::collision
