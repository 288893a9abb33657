#pragma once
// A scene, made runnable: the body model, the garment dressed on the body it
// is cut for (the mean body; a larger size's fit body, fit_body.hpp) with its
// regions' materials, and a run that morphs the body from that shape to a
// target while the garment follows (backward Euler, solver.hpp), then lets it
// settle -- the seed's ground-truth protocol (ArcSim: 2 s of morphing, 2 s of
// settling).
//
// Only what the scene names is built: an energy per effect, the body's
// closest-point hierarchy only when an effect needs the body, the per-face
// material map only when the garment's faces differ in material.
#include <drape/bodies/body.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/scene_pose.hpp>
#include <drape/physics/solver.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drape {

class Registry;

struct SimulationStep {
  int step = 0, total_steps = 0;  // total = morph + the settling budget
  bool morphing = false;
  StepReport report;
  double stationarity = -1;    // settling steps: stationarity / |weight| after the step (ClothSolver::stationarity); -1 while morphing
  double slip_ratio = 0;       // settling steps with friction: the fastest contact's slip / the slip friction holds (ClothSolver::slip_ratio)
};

struct SimulationResult {
  Eigen::MatrixX3d garment;  // final garment vertices
  Eigen::MatrixX3d body;     // the target body's vertices
  std::vector<EnergyTerm> energies;  // each effect's energy at the end (J)
  double total_energy = 0;
  double initial_energy = 0;   // on the target body, before settling (after morphing)
  double penetration = -1;     // fraction of garment vertices inside the body (-1: not measured)
  // Garment edges through body triangles and body edges through garment ones
  // at the end: the crossings p misses (no vertex inside). Empty: not measured.
  std::optional<geometry::SurfaceCrossings> crossings;
  // Garment edges through the garment's own faces at the end
  // (geometry::self_edge_crossings, all of them): a fold the
  // self-contact let through, or a scene without it. Empty: not measured.
  std::optional<int> self_crossings;
  double residual = 0;         // |grad E| / |weight| at the end
  double stationarity = 0;     // the same with both faces of a body crease counted (ClothSolver::stationarity); settles the drape
  Eigen::VectorXd vertex_force;  // N: per vertex, |grad E| less friction's push at the end (where the drape is not in equilibrium)
  Eigen::VectorXd body_distance; // m: signed distance of each garment vertex to the body (when measured)
  // Settled: stationarity <= settle_tolerance, or at rest (no vertex moved
  // more than rest_displacement in the last step) with stationarity <=
  // kink_tolerance. Where cloth lies in a concave crease of the body mesh the
  // penalty's gradient jumps between the two faces' normals and the plain
  // residual cannot fall further; stationarity counts both pushes.
  bool converged = false;
  bool at_rest = false;        // settled by the rest criterion
  double settle_tolerance = 0;  // the solver's, for the summary: at rest may settle above it
  double rest_tolerance = 0;    // the kink_tolerance at rest settles within
  double slip_ratio = 0;       // with friction: the fastest contact's slip in the last step / the slip friction holds
  bool sliding() const { return slip_ratio >= 1; }  // with friction: some contact still slid (not settled)
  // When not settled: why, in words (how far from balance, where the largest
  // unbalanced forces are, whether the steps had stopped moving).
  std::string unsettled;
  int steps = 0, iterations = 0, line_search_failures = 0;
  // With a barrier contact: morph steps split because the body's move would
  // have brought a pair too close (each part is solved before the rest of the move).
  int morph_substeps = 0;
  // m: with a barrier contact, how far the start body was shrunk along its
  // normals so that the garment starts separated from it (0: not).
  double start_shrink = 0;
  double seconds = 0;
  std::string linear_solver;
  ClothSolver::Timings timings;
};

struct SimulationOptions {
  bool measure_penetration = true;  // p and the surface crossings at the end (measurements: one closest-point pass, one crossing count)
  std::function<void(const SimulationStep&)> on_step;
  // Each partial move of a morph step the contact cut (barrier_morph.hpp):
  // the step (1-based), the run's steps, the moves so far in this step and
  // the share of the step's way the body has made. A blocked step can take
  // minutes in these; a progress bar over the steps alone sat still.
  std::function<void(int step, int total_steps, int moves, double done)> on_partial_move;
  // Overrides the start state (default: the garment dressed on the body it
  // is cut for, Simulation::fit_body(): the mean body for the regular size).
  const Eigen::MatrixX3d* start_garment = nullptr;
  const Eigen::MatrixX3d* start_body = nullptr;  // default: Simulation::fit_body()
  // A posed target (docs/poses.md): run()'s target_body is `unposed_target`
  // in `target_pose` (BodyModel::posed_vertices), and the morph turns the
  // joints as it changes the shape, along the scene's pose_path, so that the
  // contact's checks cover the arms' and legs' moves too. Both or neither.
  const Pose* target_pose = nullptr;
  const Eigen::MatrixX3d* unposed_target = nullptr;
};

class Simulation {
 public:
  // Validates the scene against the registry and builds what it names.
  Simulation(const Registry& registry, Scene scene);
  ~Simulation();

  const Scene& scene() const { return scene_; }
  const BodyModel& body_model() const { return *body_model_; }
  const Garment& garment() const { return *garment_; }
  const Eigen::MatrixX3d& mean_body() const { return mean_body_; }
  // The garment's narrowest loop over the mean body's chest band
  // (garment_size.hpp's garment_girth) before dressing moved it: as its
  // template built it, and graded by the scene's grade; infinity when it does
  // not go around the torso. What a fit is told by: dressing pushes a garment
  // smaller than the body out onto it.
  double design_loop() const { return design_loop_; }
  double placed_loop() const { return placed_loop_; }
  // The body the garment is dressed on and every run starts from: the mean
  // body, or for a garment cut larger (Garment::fit_grade) the body of its
  // girth with the mean proportions (drape/bodies/fit_body.hpp).
  const Eigen::MatrixX3d& fit_body() const { return fit_body_; }
  const BodyRequest& fit_request() const { return fit_request_; }
  // Why the garment cannot be put on fit_body() ("" when it can): its
  // cloth, measured at rest in its material space, is shorter around than
  // the body by more than a garment is stretched to be put on. run()
  // refuses such a start before any work (a caller's own start state aside).
  const std::string& start_refusal() const { return start_refusal_; }
  // A note when the garment is modelled much larger around than its cloth
  // ("" otherwise): it starts stretched and pulls in (cloth_fit.hpp). Its
  // fit notes then measure the cloth (cloth_loop), not the shape.
  const std::string& shape_note() const { return shape_note_; }
  // The garment's narrowest loop over the mean body's chest band at rest, in
  // its material space (garment_material_girth); NaN when it has none.
  double cloth_loop() const { return cloth_loop_; }
  // The scene's target body as a request (its shape: BMI, height, sex), to
  // change before solving (a command line's --girth adds proportions).
  BodyRequest target_request() const;
  // The scene's target pose (`body: {pose: ...}`); empty: the A-pose.
  const Pose& target_pose() const { return target_pose_; }
  // Shape parameters and vertices of the scene's target body, or of another request.
  Eigen::VectorXd target_shape() const;
  Eigen::VectorXd shape_for(const BodyRequest& request) const;
  Eigen::MatrixX3d body_vertices(const Eigen::VectorXd& shape) const;

  // Drapes the garment on `target_body` (the body model's topology). Thread-safe:
  // every run builds its own energies and body structure.
  SimulationResult run(const Eigen::MatrixX3d& target_body, const SimulationOptions& options = {}) const;

  // The energies of the scene's effects, bound to the garment (and to `body`
  // when an effect needs one; ConfigError when it does and body is null).
  // With `step_bounding_body`, the energies that bound steps (the barrier) are
  // bound to it instead: the physics-enforced optimisation gives the barrier a
  // body of its own that starts shrunk, while a penalty keeps the true one.
  std::vector<NamedEnergy> make_energies(const BodyQuery* body, const BodyQuery* step_bounding_body = nullptr) const;
  bool needs_body() const { return needs_body_; }
  // What the scene's effects leave out that a drape needs, in words (empty:
  // nothing): no stretching (a step may never settle), no contact with the
  // body, or a penalty contact whose stiffness or margin is 0 (the garment
  // falls through). The drape program prints each as a note; Python warns.
  std::vector<std::string> effect_notes() const;
  // The scene has a stretching effect of a stiffness_scale above 0: the
  // cloth holds its shape in the plane (a barrier morph needs it).
  bool stretches() const;

  SolverSettings solver_settings() const;

  // The body run() moves at morph time t in [0, 1], from morph_from (t = 0,
  // bit for bit) to target_body (t = 1): a straight line between the meshes,
  // or with a posed target (options.target_pose) the shape morph and the
  // joints' turn along the scene's pose_path. ConfigError when target_body is
  // not the unposed target in its pose. The function refers to its arguments:
  // they must outlive it.
  std::function<Eigen::MatrixX3d(double)> body_path(const SimulationOptions& options, const Eigen::MatrixX3d& morph_from,
                                                    const Eigen::MatrixX3d& target_body) const;

 private:

  const Registry& registry_;
  Scene scene_;
  std::unique_ptr<BodyModel> body_model_;
  std::shared_ptr<Garment> garment_;
  Eigen::MatrixX3d mean_body_;
  double design_loop_ = 0.0, placed_loop_ = 0.0;
  Eigen::MatrixX3d fit_body_;
  Eigen::MatrixX3d undressed_;  // the garment's vertices before dressing on fit_body_ (before a graded garment's placing)
  std::vector<int> placed_through_;  // dressing found these vertices placed through the body (DressReport::pushed_through; empty below kThroughCount)
  double placed_through_depth_ = 0;  // m, the deepest of them
  std::string beside_body_;          // garment_beside_body of the garment as placed: empty when it goes around the body
  [[noreturn]] void rethrow_with_offset_hint(const ConfigError& refused, const SimulationOptions& options) const;
  BodyRequest fit_request_;
  std::string start_refusal_, shape_note_;
  double cloth_loop_ = 0.0;
  std::vector<std::string> material_notes_;  // a base's material a `region: null` dropped (effect_notes)
  bool sized_ = false;  // the garment has sizes to choose from (size: auto); else grade: auto is the remedy named
  std::vector<Params> effect_params_;
  bool needs_body_ = false;
  int morph_steps_ = 0, settle_steps_ = 0, morph_newton_ = 3;
  std::pair<double, double> morph_carry_;  // solver morph_carry: [inner, outer] m
  std::string settle_check_ = "iteration";  // solver settle_check: when settledness is checked
  Pose target_pose_;
  PosePath pose_path_ = PosePath::together;
  Eigen::Vector3d gravity_direction_{0, -1, 0};
};

}  // namespace drape
