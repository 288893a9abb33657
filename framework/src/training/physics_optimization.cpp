#include <drape/energy.hpp>
#include <drape/training/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/training/optimizer.hpp>
#include <drape/training/physics_optimization.hpp>

#include "../scene/vertexwise_growth.hpp"
#include "../scene/separated_start.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>

namespace drape {

namespace {

// L_p and its gradient at x: every energy of the scene, in double; the
// step-bounding ones (the barrier) only when `with_bounding`.
double potential(std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x, Eigen::MatrixX3d& gradient,
                 std::vector<EnergyTerm>* terms, bool with_bounding) {
  gradient.setZero(x.rows(), 3);
  if (terms) terms->clear();
  double total = 0;
  for (NamedEnergy& e : energies) {
    if (e.energy->bounds_steps() && !with_bounding) continue;
    const double value = e.energy->add_gradient(x, gradient);
    if (!std::isfinite(value)) throw Error("optimize: the " + e.name + " energy is not finite");
    total += value;
    if (terms) terms->push_back({e.name, value});
  }
  if (!gradient.allFinite()) throw Error("optimize: the energy gradient is not finite");
  return total;
}

// The largest fraction of the move x -> x + dx (with the barrier's body moving
// from body_from to body_to, when given) that the step-bounding energies allow.
double allowed_step(const std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx,
                    const Eigen::MatrixX3d* body_from = nullptr, const Eigen::MatrixX3d* body_to = nullptr) {
  double alpha = 1;
  for (const NamedEnergy& e : energies)
    if (e.energy->bounds_steps()) alpha = std::min(alpha, e.energy->max_step(x, dx, body_from, body_to));
  return alpha;
}

// The network's weights at one iterate.
struct WeightSnapshot {
  std::vector<Tensor> weights;
  void save(const Optimizer& o) {
    weights.resize(o.weights().size());  // copied into the same buffers at every save
    for (std::size_t k = 0; k < weights.size(); ++k) weights[k] = o.weights()[k].second->value;
  }
  void restore(Optimizer& o) const {
    for (std::size_t k = 0; k < weights.size(); ++k) o.weights()[k].second->value = weights[k];
  }
};

// The last accepted step, to go back to after a refused one: weights and Adam's moments.
struct Accepted {
  WeightSnapshot snapshot;
  OptimizerState optimizer;
  void save(const Optimizer& o) {
    snapshot.save(o);
    optimizer = o.state();
  }
  void restore(Optimizer& o) const {
    snapshot.restore(o);
    o.set_state(optimizer);
  }
};

// Refused steps in a row (each at least halving the learning rate) before the
// drape is taken as stuck against the body: 2^-30 of the step is below float
// round-off.
constexpr int kMaxRefusalsInARow = 30;
// A refused step is retried at this share of the fraction the collision
// checks allow (IPC's line search starts at 0.8 of its bound too)...
constexpr double kAllowedStepShare = 0.8;
// ...but its learning rate is never cut to less than this at once.
constexpr double kSmallestRetry = 1.0 / 64;

void check_request(Model& model, const Simulation& scene, const SampleBatch& body,
                   const PhysicsOptimizationOptions& options) {
  if (body.size() != 1) throw ConfigError("optimize: one body at a time, got " + std::to_string(body.size()));
  if (options.iterations < 0) throw ConfigError("optimize: iterations must be >= 0");
  if (!(options.learning_rate > 0)) throw ConfigError("optimize: the learning rate must be > 0");
  const Mesh& garment = scene.garment().mesh;
  const Mesh& trained = model.assets().garment->mesh;
  if (garment.num_vertices() != trained.num_vertices() || garment.faces != trained.faces)
    throw ConfigError("optimize: the scene's garment (" + std::to_string(garment.num_vertices()) +
                      " vertices) is not the template the model was trained on (" +
                      std::to_string(trained.num_vertices()) + " vertices): give a scene with the same template, size "
                      "and resolution");
}

bool has_barrier(const std::vector<NamedEnergy>& energies) {
  return std::any_of(energies.begin(), energies.end(), [](const NamedEnergy& e) { return e.energy->bounds_steps(); });
}

// Growing each region of the body up to the barrier's reach of the cloth
// (not into it) finished 157 of the 4k model's 200 test bodies in 100
// iterations, against 121 with the whole body at one pace; up to twice the
// reach 145, half of it 150, a quarter 129 (docs/optimization.md).
double barrier_reach(const std::vector<NamedEnergy>& energies) {
  double growth_floor = 0;
  for (const NamedEnergy& e : energies)
    if (e.energy->bounds_steps()) growth_floor = std::max(growth_floor, e.energy->activation_distance());
  return growth_floor;
}

// With a barrier (an energy that bounds steps) no accepted drape crosses the
// body. A barrier keeps separated surfaces apart but cannot see through a
// crossing one, and a network's prediction usually crosses the body
// somewhere. So, as the simulation does, the barrier starts on the body
// shrunk along its normals by the least of 0.5-6 cm that separates the
// prediction, and the body grows back to its true shape, each region as far
// as the continuous collision checks allow after every step, the barrier
// pushing the cloth out ahead of it. Every weight step is checked over the
// straight move from the last accepted drape: one that would cross is undone
// and retried shorter. Only drapes on the fully grown body are results
// (docs/optimization.md).
//
// One drape's optimisation: start (the prediction, and the shrunk body that
// separates it), iterate (Adam steps on the weights, each checked against the
// body), conclude (the best drape on the true body, or why there is none).
class DrapeOptimization {
 public:
  DrapeOptimization(Model& model, const Simulation& scene, const SampleBatch& body,
                    const PhysicsOptimizationOptions& options)
      : model_(model),
        options_(options),
        garment_(scene.garment().mesh),
        body_vertices_(body.body.mat(0).cast<double>()),
        body_faces_(model.assets().body.faces),
        surface_(body_vertices_, body_faces_),
        barrier_surface_(body_vertices_, body_faces_),
        energies_(scene.make_energies(scene.needs_body() ? &surface_ : nullptr, &barrier_surface_)),
        bounded_(has_barrier(energies_)),
        growth_floor_(barrier_reach(energies_)),
        garment_faces_(garment_.faces),
        graph_(model.graph()),
        inputs_(graph_inputs(graph_, body, false)),
        twin_inputs_(model.mirror_average_node().empty() ? std::map<std::string, Tensor>{}
                                                          : graph_inputs(graph_, model.mirrored_batch(body), false)),
        adam_(graph_.weights()),
        fresh_moments_(adam_.state()),
        grad_(1, garment_.num_vertices(), 3),
        body_now_(body_vertices_),
        vertexwise_growth_(body_faces_, garment_faces_),
        cloth_still_(Eigen::MatrixX3d::Zero(garment_.num_vertices(), 3)) {}
  DrapeOptimization(const DrapeOptimization&) = delete;  // the energies hold the surfaces' addresses
  DrapeOptimization& operator=(const DrapeOptimization&) = delete;

  void start();
  void iterate();
  PhysicsOptimizationResult conclude();

 private:
  Eigen::MatrixX3d predict();
  void backward();
  void evaluate(int it);
  double body_move_allowed(const Eigen::MatrixX3d& to) {
    return allowed_step(energies_, x_, cloth_still_, &body_now_, &to);
  }
  void grow_body();
  void start_on_shrunk_body();
  void explain_unseparated();

  Model& model_;
  const PhysicsOptimizationOptions& options_;
  const Mesh& garment_;
  const Eigen::MatrixX3d body_vertices_;
  const Eigen::MatrixX3i& body_faces_;
  // p is measured on the true body whether or not the scene has collisions
  // (it is the seed's metric), so its surface always exists.
  const geometry::BodySurface surface_;
  // The barrier gets a body of its own, which may start shrunk (below); a
  // penalty contact beside it keeps the true body and pushes the cloth out of it.
  geometry::BodySurface barrier_surface_;
  std::vector<NamedEnergy> energies_;
  const bool bounded_;
  const double growth_floor_;
  const Eigen::MatrixX3i& garment_faces_;

  Graph& graph_;
  const std::map<std::string, Tensor> inputs_;
  // With the mirror average (Model::forward), the twin's inputs: the drape
  // optimised is the model's mean, and the gradient reaches the weights
  // through both passes (backward()).
  const std::map<std::string, Tensor> twin_inputs_;
  Adam adam_;
  const OptimizerState fresh_moments_;
  PhysicsOptimizationResult r_;
  Eigen::MatrixX3d x_, gradient_;
  Tensor grad_;
  bool with_barrier_ = false;  // the barrier acts: the drape is clear of the body the contact sees
  Eigen::MatrixX3d body_now_;  // the body the contact sees: shrunk, growing back
  bool grown_ = true;
  double start_gap_ = 0;  // |true body - shrunk start body|
  double best_ = INFINITY;
  // The weights of the best drape: the model is left predicting `after`, not
  // the last iterate, which can be a little worse (Adam overshoots). The run
  // ends there, so Adam's moments are not kept with them: one copy of the
  // weights per better iterate, not three.
  WeightSnapshot best_weights_;
  std::vector<EnergyTerm> terms_;  // of the latest drape
  // The body grows towards its true shape as far as no pair comes too close:
  // first each vertex as far as its own pairs' collision checks allow, and
  // no nearer the cloth than the barrier's reach (vertexwise_growth.hpp; the
  // contact's checks confirm the whole move), then the whole body on by the
  // fraction of the rest that the checks allow, which brings the closest
  // pair into the barrier's reach so that it pushes the cloth out.
  const scene_detail::VertexwiseGrowth vertexwise_growth_;
  const Eigen::MatrixX3d cloth_still_;
  Accepted accepted_;
  Eigen::MatrixX3d push_offset_;  // the push-out's correction of the prediction, added to the network's drape (start())
};

Eigen::MatrixX3d DrapeOptimization::predict() {
  // The network's own drape: the push-out after it is not learnt (Model::forward_network).
  const Tensor& garment = model_.forward_network(inputs_, twin_inputs_.empty() ? nullptr : &twin_inputs_);
  Eigen::MatrixX3d out = garment.mat(0).cast<double>();
  if (!out.allFinite())
    throw Error("optimize: the network predicted a non-finite vertex at iteration " + std::to_string(r_.history.size()));
  // The push-out's correction of the prediction, frozen (start()).
  if (push_offset_.rows()) out += push_offset_;
  return out;
}

// The gradient of L_p at the last predicted drape into the weights
// (Model::backward: with the mirror average, through both passes).
void DrapeOptimization::backward() {
  graph_.zero_grad();
  grad_.mat(0) = gradient_.cast<float>();
  model_.backward_network(grad_, twin_inputs_.empty() ? nullptr : &twin_inputs_);
}

void DrapeOptimization::evaluate(int it) {
  std::vector<EnergyTerm> evaluated_terms;  // kept only once the whole potential is known
  const double lp = potential(energies_, x_, gradient_, &evaluated_terms, with_barrier_);
  terms_ = std::move(evaluated_terms);
  r_.history.push_back(lp);
  if (options_.on_iteration) options_.on_iteration(it, lp);
  if (it == 0) {
    r_.before = x_;
    r_.energies_before = terms_;
    r_.potential_before = lp;
  }
  if (grown_ && with_barrier_ == bounded_ && lp < best_) {
    best_ = lp;
    r_.after = x_;
    r_.energies_after = terms_;
    r_.potential_after = lp;
    r_.best_iteration = it;
    best_weights_.save(adam_);
  }
}

void DrapeOptimization::grow_body() {
  const Eigen::MatrixX3d grown_by_vertex = vertexwise_growth_.step(body_now_, body_vertices_, x_, growth_floor_);
  body_now_ += body_move_allowed(grown_by_vertex) * (grown_by_vertex - body_now_);
  const double alpha = body_move_allowed(body_vertices_);
  body_now_ = alpha >= 1 ? body_vertices_ : Eigen::MatrixX3d(body_now_ + alpha * (body_vertices_ - body_now_));
  grown_ = alpha >= 1;
  barrier_surface_.update(body_now_);
  if (grown_) {
    r_.grown_iteration = static_cast<int>(r_.history.size());
    // The growth pushed the cloth out through the weights with the
    // barrier's large, brief gradients; Adam's moments remember them for
    // hundreds of steps and would damp the minimisation on the true body
    // that starts now (4k model, 200 test bodies: ME 2.135 -> 1.987 cm with
    // fresh moments, on the 95 bodies every growth rule tried finished).
    adam_.set_state(fresh_moments_);
  }
}

// A prediction that crosses the body: the barrier starts on the body shrunk
// until it is clear of the prediction.
void DrapeOptimization::start_on_shrunk_body() {
  try {
    body_now_ = scene_detail::separated_start_body(x_, body_vertices_, body_faces_, garment_faces_, &r_.start_shrink);
    grown_ = false;
    r_.grown_iteration = -1;
    start_gap_ = (body_vertices_ - body_now_).norm();
    barrier_surface_.update(body_now_);
    with_barrier_ = true;
    potential(energies_, x_, gradient_, nullptr, true);  // the first step's gradient, against the shrunk body
  } catch (const ConfigError& e) {
    r_.unseparated = e.what();  // the other energies still act, but nothing is a result
  }
}

void DrapeOptimization::start() {
  // A model that ends in a push-out: the drape optimised is the network's
  // own plus the push-out's correction of the prediction, frozen: the
  // prediction itself at the start (clear of the body, where the push-out
  // put it), and moved by the weights exactly as the network's drape is, so
  // that the potential's gradient is the weights' (the push-out is not
  // learnt, and run at every iteration it had moved vertices the gradient
  // then credited to the weights: the potential rose; docs/optimization.md).
  // (The prediction is own + correction: the network is not run a third time.)
  if (!model_.push_out_node().empty()) {
    const Eigen::MatrixX3d own = predict();
    const Tensor& pushed = model_.forward(inputs_, twin_inputs_.empty() ? nullptr : &twin_inputs_);
    push_offset_ = pushed.mat(0).cast<double>() - own;
    if (!push_offset_.allFinite()) throw Error("optimize: the model's push-out gave a non-finite vertex");
    x_ = own + push_offset_;
  } else {
    x_ = predict();
  }
  // L_p before is the prediction's on the true body; the barrier counts in it
  // only when the prediction is clear of the body (it cannot see a crossing).
  with_barrier_ = bounded_ && scene_detail::separation_problem(x_, surface_, garment_faces_).empty();
  evaluate(0);
  if (bounded_ && !with_barrier_) start_on_shrunk_body();
  if (with_barrier_) accepted_.save(adam_);
}

void DrapeOptimization::iterate() {
  double scale = 1;  // of the learning rate, halved at each refused step
  int refused_in_a_row = 0;
  Eigen::MatrixX3d evaluated = x_;  // the last drape whose potential is known
  try {
    for (int it = 1; it <= options_.iterations;) {
      backward();
      adam_.step(options_.learning_rate * scale);
      Eigen::MatrixX3d next = predict();
      const double allowed = with_barrier_ ? allowed_step(energies_, x_, next - x_) : 1.0;
      if (allowed < 1) {
        ++r_.refused_steps;
        if (++refused_in_a_row > kMaxRefusalsInARow) break;  // stuck against the body: the best drape stands
        accepted_.restore(adam_);
        x_ = predict();  // the accepted drape again, and the activations its backward pass needs
        // From the restored moments Adam's step is proportional to the learning
        // rate, so to first order the drape then moves by that fraction of
        // next - x: retry at a little less than the fraction the collision
        // checks allow, and at least halve (the network is not linear in its
        // weights). Halving alone took several refusals per contact-bound step.
        scale *= std::clamp(kAllowedStepShare * allowed, kSmallestRetry, 0.5);
        continue;
      }
      refused_in_a_row = 0;
      scale = std::min(1.0, 2 * scale);
      x_ = std::move(next);
      if (with_barrier_ && !grown_) grow_body();
      evaluate(it++);
      evaluated = x_;
      if (with_barrier_) accepted_.save(adam_);
    }
  } catch (const Error& e) {
    // One sample's failure (a pair at distance 0 that rounding let through
    // the checks: the barrier cannot be evaluated there) must not end a run
    // of hundreds. The drapes evaluated before stand; `grown` and the best
    // drape are only ever set from those.
    r_.stopped = "stopped after iteration " + std::to_string(r_.history.size() - 1) + ": " + e.what();
    x_ = evaluated;
  }
}

// No drape on the true body that is known to be clear of it: the last one is
// returned, with why it is not a result.
void DrapeOptimization::explain_unseparated() {
  r_.after = x_;
  r_.energies_after = terms_;
  r_.potential_after = r_.history.back();
  r_.best_iteration = static_cast<int>(r_.history.size()) - 1;
  if (!r_.stopped.empty()) {
    r_.unseparated = r_.stopped;
  } else if (with_barrier_) {
    const double left = (body_vertices_ - body_now_).norm() / std::max(start_gap_, 1e-300);
    char why[200];
    std::snprintf(why, sizeof why,
                  "the body, shrunk by %.1f cm to separate the prediction, grew back only %.0f %% of the way in %d "
                  "iterations: give more iterations",
                  100 * r_.start_shrink, 100 * (1 - left), options_.iterations);
    r_.unseparated = why;
  }
}

PhysicsOptimizationResult DrapeOptimization::conclude() {
  // A stop in the growth can leave `grown` set with no drape evaluated on the
  // true body: only an evaluated best is a result.
  r_.separated = !bounded_ || (with_barrier_ && grown_ && std::isfinite(best_));
  // After a stop the model holds the weights of the step that failed.
  const bool weights_past_last_drape = !r_.stopped.empty();
  if (r_.separated && (weights_past_last_drape || r_.best_iteration + 1 != static_cast<int>(r_.history.size())))
    best_weights_.restore(adam_);
  if (!r_.separated && weights_past_last_drape && with_barrier_) accepted_.restore(adam_);
  if (!r_.separated) explain_unseparated();
  r_.penetration_before = geometry::penetration_ratio(surface_, r_.before);
  r_.penetration_after = geometry::penetration_ratio(surface_, r_.after);
  return std::move(r_);
}

}  // namespace

PhysicsOptimizationResult optimize_drape(Model& model, const Simulation& scene, const SampleBatch& body,
                                         const PhysicsOptimizationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // One drape is too little work to split across cores: with OpenMP teams on a
  // busy machine an iteration took 20x longer (380 against 18 ms, coarse shirt).
  // Callers optimising many drapes run one per core instead.
  const OmpThreadsScope one_core(1);
  check_request(model, scene, body, options);
  DrapeOptimization optimization(model, scene, body, options);
  optimization.start();
  optimization.iterate();
  PhysicsOptimizationResult r = optimization.conclude();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace drape
