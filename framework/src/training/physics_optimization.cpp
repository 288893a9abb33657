#include <drape/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/optimizer.hpp>
#include <drape/physics_optimization.hpp>

#include <chrono>
#include <cmath>
#include <memory>

namespace drape {

namespace {

// L_p and its gradient at x: every energy of the scene, in double.
double potential(std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x, Eigen::MatrixX3d& gradient,
                 std::vector<EnergyTerm>* terms) {
  gradient.setZero(x.rows(), 3);
  if (terms) terms->clear();
  double total = 0;
  for (NamedEnergy& e : energies) {
    const double value = e.energy->add_gradient(x, gradient);
    if (!std::isfinite(value)) throw Error("optimize: the " + e.name + " energy is not finite");
    total += value;
    if (terms) terms->push_back({e.name, value});
  }
  if (!gradient.allFinite()) throw Error("optimize: the energy gradient is not finite");
  return total;
}

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
  std::unique_ptr<geometry::BodySurface> surface;
  if (scene.needs_body()) surface = std::make_unique<geometry::BodySurface>(body_vertices, model.assets().body.faces);
  std::vector<NamedEnergy> energies = scene.make_energies(surface.get());

  Graph& graph = model.graph();
  const auto inputs = graph_inputs(graph, body, false);
  Adam adam(graph.weights());
  PhysicsOptimizationResult r;
  Eigen::MatrixX3d x, gradient;
  Tensor grad(1, garment.num_vertices(), 3);
  double best = INFINITY;
  for (int it = 0;; ++it) {
    graph.forward(inputs, false);
    x = graph.output(model.output()).mat(0).cast<double>();
    if (!x.allFinite()) throw Error("optimize: the network predicted a non-finite vertex at iteration " + std::to_string(it));
    std::vector<EnergyTerm> terms;
    const double lp = potential(energies, x, gradient, &terms);
    r.history.push_back(lp);
    if (options.on_iteration) options.on_iteration(it, lp);
    if (it == 0) {
      r.before = x;
      r.energies_before = terms;
      r.potential_before = lp;
    }
    if (lp < best) {
      best = lp;
      r.after = x;
      r.energies_after = terms;
      r.potential_after = lp;
      r.best_iteration = it;
    }
    if (it == options.iterations) break;
    grad.mat(0) = gradient.cast<float>();
    graph.zero_grad();
    graph.backward_from_output(model.output(), grad);
    adam.step(options.learning_rate);
  }
  // p is measured whether or not the scene has collisions (it is the seed's metric).
  if (!surface) surface = std::make_unique<geometry::BodySurface>(body_vertices, model.assets().body.faces);
  r.penetration_before = geometry::penetration_ratio(*surface, r.before);
  r.penetration_after = geometry::penetration_ratio(*surface, r.after);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace drape
