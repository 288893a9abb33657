#include <drape/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/optimizer.hpp>
#include <drape/physics_optimization.hpp>

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

}  // namespace

PhysicsOptimizationResult optimize_drape(Model& model, const Simulation& scene, const SampleBatch& body,
                                         const PhysicsOptimizationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // One drape is too little work to split across cores: with OpenMP teams on a
  // busy machine an iteration took 20x longer (380 against 18 ms, coarse shirt).
  // Callers optimising many drapes run one per core instead.
  const OmpThreadsScope one_core(1);
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

  const Eigen::MatrixX3d body_vertices = body.body.mat(0).cast<double>();
  const Eigen::MatrixX3i& body_faces = model.assets().body.faces;
  // p is measured on the true body whether or not the scene has collisions
  // (it is the seed's metric), so its surface always exists.
  const geometry::BodySurface surface(body_vertices, body_faces);
  // The barrier gets a body of its own, which may start shrunk (below); a
  // penalty contact beside it keeps the true body and pushes the cloth out of it.
  geometry::BodySurface barrier_surface(body_vertices, body_faces);
  std::vector<NamedEnergy> energies = scene.make_energies(scene.needs_body() ? &surface : nullptr, &barrier_surface);

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
  const bool bounded = std::any_of(energies.begin(), energies.end(), [](const NamedEnergy& e) { return e.energy->bounds_steps(); });
  // Growing each region of the body up to the barrier's reach of the cloth
  // (not into it) finished 157 of the 4k model's 200 test bodies in 100
  // iterations, against 121 with the whole body at one pace; up to twice the
  // reach 145, half of it 150, a quarter 129 (docs/optimization.md).
  double growth_floor = 0;
  for (const NamedEnergy& e : energies)
    if (e.energy->bounds_steps()) growth_floor = std::max(growth_floor, e.energy->activation_distance());
  const Eigen::MatrixX3i& garment_faces = garment.faces;

  Graph& graph = model.graph();
  const auto inputs = graph_inputs(graph, body, false);
  Adam adam(graph.weights());
  const OptimizerState fresh_moments = adam.state();
  PhysicsOptimizationResult r;
  Eigen::MatrixX3d x, gradient;
  Tensor grad(1, garment.num_vertices(), 3);
  auto predict = [&]() -> Eigen::MatrixX3d {
    graph.forward(inputs, false);
    Eigen::MatrixX3d out = graph.output(model.output()).mat(0).cast<double>();
    if (!out.allFinite())
      throw Error("optimize: the network predicted a non-finite vertex at iteration " + std::to_string(r.history.size()));
    return out;
  };
  bool with_barrier = false;  // the barrier acts: the drape is clear of the body the contact sees
  Eigen::MatrixX3d body_now = body_vertices;  // the body the contact sees: shrunk, growing back
  bool grown = true;
  double start_gap = 0;  // |true body - shrunk start body|
  double best = INFINITY;
  // The weights of the best drape: the model is left predicting `after`, not
  // the last iterate, which can be a little worse (Adam overshoots). The run
  // ends there, so Adam's moments are not kept with them: one copy of the
  // weights per better iterate, not three.
  WeightSnapshot best_weights;
  std::vector<EnergyTerm> terms;  // of the latest drape
  auto evaluate = [&](int it) {
    std::vector<EnergyTerm> evaluated_terms;  // kept only once the whole potential is known
    const double lp = potential(energies, x, gradient, &evaluated_terms, with_barrier);
    terms = std::move(evaluated_terms);
    r.history.push_back(lp);
    if (options.on_iteration) options.on_iteration(it, lp);
    if (it == 0) {
      r.before = x;
      r.energies_before = terms;
      r.potential_before = lp;
    }
    if (grown && with_barrier == bounded && lp < best) {
      best = lp;
      r.after = x;
      r.energies_after = terms;
      r.potential_after = lp;
      r.best_iteration = it;
      best_weights.save(adam);
    }
  };
  // The body grows towards its true shape as far as no pair comes too close:
  // first each vertex as far as its own pairs' collision checks allow, and
  // no nearer the cloth than the barrier's reach (vertexwise_growth.hpp; the
  // contact's checks confirm the whole move), then the whole body on by the
  // fraction of the rest that the checks allow, which brings the closest
  // pair into the barrier's reach so that it pushes the cloth out.
  const scene_detail::VertexwiseGrowth vertexwise_growth(body_faces, garment_faces);
  const Eigen::MatrixX3d cloth_still = Eigen::MatrixX3d::Zero(garment.num_vertices(), 3);
  auto body_move_allowed = [&](const Eigen::MatrixX3d& to) { return allowed_step(energies, x, cloth_still, &body_now, &to); };
  auto grow_body = [&]() {
    const Eigen::MatrixX3d grown_by_vertex = vertexwise_growth.step(body_now, body_vertices, x, growth_floor);
    body_now += body_move_allowed(grown_by_vertex) * (grown_by_vertex - body_now);
    const double alpha = body_move_allowed(body_vertices);
    body_now = alpha >= 1 ? body_vertices : Eigen::MatrixX3d(body_now + alpha * (body_vertices - body_now));
    grown = alpha >= 1;
    barrier_surface.update(body_now);
    if (grown) {
      r.grown_iteration = static_cast<int>(r.history.size());
      // The growth pushed the cloth out through the weights with the
      // barrier's large, brief gradients; Adam's moments remember them for
      // hundreds of steps and would damp the minimisation on the true body
      // that starts now (4k model, 200 test bodies: ME 2.135 -> 1.987 cm with
      // fresh moments, on the 95 bodies every growth rule tried finished).
      adam.set_state(fresh_moments);
    }
  };

  x = predict();
  // L_p before is the prediction's on the true body; the barrier counts in it
  // only when the prediction is clear of the body (it cannot see a crossing).
  with_barrier = bounded && scene_detail::separation_problem(x, surface, garment_faces).empty();
  evaluate(0);
  if (bounded && !with_barrier) {
    try {
      body_now = scene_detail::separated_start_body(x, body_vertices, body_faces, garment_faces, &r.start_shrink);
      grown = false;
      r.grown_iteration = -1;
      start_gap = (body_vertices - body_now).norm();
      barrier_surface.update(body_now);
      with_barrier = true;
      potential(energies, x, gradient, nullptr, true);  // the first step's gradient, against the shrunk body
    } catch (const ConfigError& e) {
      r.unseparated = e.what();  // the other energies still act, but nothing is a result
    }
  }
  Accepted accepted;
  if (with_barrier) accepted.save(adam);
  double scale = 1;  // of the learning rate, halved at each refused step
  int refused_in_a_row = 0;
  Eigen::MatrixX3d evaluated = x;  // the last drape whose potential is known
  try {
    for (int it = 1; it <= options.iterations;) {
      grad.mat(0) = gradient.cast<float>();
      graph.zero_grad();
      graph.backward_from_output(model.output(), grad);
      adam.step(options.learning_rate * scale);
      Eigen::MatrixX3d next = predict();
      const double allowed = with_barrier ? allowed_step(energies, x, next - x) : 1.0;
      if (allowed < 1) {
        ++r.refused_steps;
        if (++refused_in_a_row > kMaxRefusalsInARow) break;  // stuck against the body: the best drape stands
        accepted.restore(adam);
        x = predict();  // the accepted drape again, and the activations its backward pass needs
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
      x = std::move(next);
      if (with_barrier && !grown) grow_body();
      evaluate(it++);
      evaluated = x;
      if (with_barrier) accepted.save(adam);
    }
  } catch (const Error& e) {
    // One sample's failure (a pair at distance 0 that rounding let through
    // the checks: the barrier cannot be evaluated there) must not end a run
    // of hundreds. The drapes evaluated before stand; `grown` and the best
    // drape are only ever set from those.
    r.stopped = "stopped after iteration " + std::to_string(r.history.size() - 1) + ": " + e.what();
    x = evaluated;
  }
  // A stop in the growth can leave `grown` set with no drape evaluated on the
  // true body: only an evaluated best is a result.
  r.separated = !bounded || (with_barrier && grown && std::isfinite(best));
  // After a stop the model holds the weights of the step that failed.
  const bool weights_past_last_drape = !r.stopped.empty();
  if (r.separated && (weights_past_last_drape || r.best_iteration + 1 != static_cast<int>(r.history.size())))
    best_weights.restore(adam);
  if (!r.separated && weights_past_last_drape && with_barrier) accepted.restore(adam);
  if (!r.separated) {
    // No drape on the true body that is known to be clear of it: return the
    // last one, and say why it is not a result.
    r.after = x;
    r.energies_after = terms;
    r.potential_after = r.history.back();
    r.best_iteration = static_cast<int>(r.history.size()) - 1;
    if (!r.stopped.empty()) {
      r.unseparated = r.stopped;
    } else if (with_barrier) {
      const double left = (body_vertices - body_now).norm() / std::max(start_gap, 1e-300);
      char why[200];
      std::snprintf(why, sizeof why,
                    "the body, shrunk by %.1f cm to separate the prediction, grew back only %.0f %% of the way in %d "
                    "iterations: give more iterations",
                    100 * r.start_shrink, 100 * (1 - left), options.iterations);
      r.unseparated = why;
    }
  }
  r.penetration_before = geometry::penetration_ratio(surface, r.before);
  r.penetration_after = geometry::penetration_ratio(surface, r.after);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace drape
