#pragma once
// Physics terms in double precision on a garment state. The simulator sums the
// energies a scene names; EnergyNode exposes any energy as a graph loss so the
// same code serves simulation, training and per-sample optimisation.
#include <drape/mesh.hpp>
#include <drape/physics/material.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class Dissipation;  // physics/dissipation.hpp

// Closest-point queries against a body surface (implemented by the geometry layer).
class BodyQuery {
 public:
  virtual ~BodyQuery() = default;
  struct Hit {
    Eigen::Vector3d point;
    Eigen::Vector3d normal;  // outward, unit
    double signed_distance;  // < 0 inside the body
  };
  virtual Hit closest(const Eigen::Vector3d& p) const = 0;
};

// The garment an energy acts on. Material space is the UV layout in meters.
struct Garment {
  Mesh mesh;                          // rest (dressed) state + material-space uv per corner
  std::vector<Material> materials;    // at least one
  Eigen::VectorXi face_material;      // [F] index into materials; empty = all 0
  // The girth of the body the garment is cut for, as a multiple of the body
  // model's mean body's (1: the mean body). A template's larger sizes set it
  // to their grade and grade_garment multiplies it; a scene dresses the
  // garment on the body of that girth and starts its morph there (fit_body,
  // drape/bodies/fit_body.hpp).
  double fit_grade = 1.0;
  // The body model whose mean body the template fits the garment to (a
  // MakeHuman outfit's .mhclo binds it to MakeHuman's body); empty: it is
  // modelled around whichever body model's mean body the scene names (the
  // tshirt template, a mesh file). A scene with another body model is
  // refused at once, naming both.
  std::string body_model;
  // The vertices as the template or file placed them, before dress() moved
  // them out of the body ([V, 3]; empty: mesh.vertices). Where the
  // self-contact finds the fabric neighbours it leaves out (close at rest):
  // dressed, a garment placed through the body had vertices 14 mm apart
  // pushed together onto the body, and the pairs between them, left out,
  // passed through each other in the morph. (ABI 11.)
  Eigen::MatrixX3d cut_vertices;
  int material_of(int face) const { return face_material.size() ? face_material[face] : 0; }
  // cut_vertices, or mesh.vertices when it holds none.
  const Eigen::MatrixX3d& as_cut() const { return cut_vertices.rows() == mesh.vertices.rows() ? cut_vertices : mesh.vertices; }
};

struct EnergyContext {
  const Garment* garment = nullptr;
  const BodyQuery* body = nullptr;  // null unless the scene needs collisions
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};
};

using Triplets = std::vector<Eigen::Triplet<double>>;

class Energy {
 public:
  virtual ~Energy() = default;
  // Precompute whatever depends only on the rest state (areas, inverse rest matrices).
  virtual void bind(const EnergyContext& context) = 0;
  virtual double value(const Eigen::MatrixX3d& x) const = 0;
  // Adds dE/dx to g ([V, 3]) and returns E.
  virtual double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const = 0;
  // Appends the Hessian as triplets on the flattened index 3*vertex + axis.
  // With project_psd, each element block is projected to the nearest PSD matrix
  // (what Newton needs); without, it is the exact Hessian (what tests compare).
  virtual void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const = 0;
  // The same matrix's entries with row >= column only: what the solver stores
  // of the symmetric Newton matrix, and about half the triplets to write and
  // assemble. This default filters add_hessian's; element energies write the
  // lower triangle directly (element_assembly.hpp).
  virtual void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const {
    const std::size_t start = h.size();
    add_hessian(x, h, project_psd);
    h.erase(std::remove_if(h.begin() + static_cast<std::ptrdiff_t>(start), h.end(),
                           [](const Eigen::Triplet<double>& t) { return t.row() < t.col(); }),
            h.end());
  }
  // True when bind() needs EnergyContext::body. The simulator builds the body's
  // closest-point structure only when some active energy asks for it.
  virtual bool needs_body() const { return false; }
  // True for an energy that is a sum of per-vertex terms and not
  // differentiable everywhere (the exact body contact: its gradient jumps
  // where the closest body face switches across a crease). Such an energy
  // implements vertex_gradient_samples: it appends its gradient at `vertex`
  // evaluated with that vertex moved by `radius` along +-x, +-y, +-z (the
  // others fixed). The solver's stationarity measure takes the convex hull of
  // these samples, Goldstein's epsilon-subdifferential (solver.hpp).
  virtual bool has_kinks() const { return false; }
  // The largest fraction alpha in [0, 1] of the move x -> x + dx (with the
  // body moving from `body_from` to `body_to` over the same interval when
  // they are given, else standing still) along which this energy stays
  // finite: a barrier contact returns where its closest pair would come too
  // close (continuous collision detection), so a line search that starts at
  // alpha never lets the surfaces cross. Energies finite everywhere return 1.
  virtual double max_step(const Eigen::MatrixX3d& /*x*/, const Eigen::MatrixX3d& /*dx*/,
                          const Eigen::MatrixX3d* /*body_from*/ = nullptr,
                          const Eigen::MatrixX3d* /*body_to*/ = nullptr) const {
    return 1.0;
  }
  // True when max_step can return less than 1 (a barrier contact): the
  // simulator then carries the garment with the morphing body and checks
  // every body move, since a state this energy calls infinite must never be entered.
  virtual bool bounds_steps() const { return false; }
  // For a step-bounding energy: the distance (m) within which a pair costs
  // anything (a barrier's d_hat); 0 for the others. `drape optimize` grows a
  // shrunk body back up to this gap from the cloth before it lets the barrier
  // take over (docs/optimization.md).
  virtual double activation_distance() const { return 0; }
  virtual void vertex_gradient_samples(const Eigen::MatrixX3d& /*x*/, int /*vertex*/, double /*radius*/,
                                       std::vector<Eigen::Vector3d>& /*samples*/) const {}

  // The dissipative potential that goes with this energy's contacts
  // (friction, physics/dissipation.hpp: its own potential, lagged per time
  // step), owned by the energy; null for every other energy and for a contact
  // without friction. The solver adds it to each step's incremental potential.
  virtual Dissipation* dissipation() { return nullptr; }
};

}  // namespace drape
