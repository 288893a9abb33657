#pragma once
// The seed's physics-enforced optimisation (Sec. 6.4): fine-tune a network's
// weights for one body so that the garment it predicts minimises the scene's
// potential energy L_p (gravity + stretching + bending + penetration: the
// effects the scene names, in double precision), back-propagating the energy
// gradient through the network (Graph::backward_from_output) and stepping the
// weights with Adam. This fixes residual penetrations and stretch of the
// prediction and adapts it to materials never seen in training (a scene with a
// print).
#include <drape/training/model.hpp>
#include <drape/scene/simulation.hpp>

#include <functional>
#include <string>
#include <vector>

namespace drape {

struct PhysicsOptimizationOptions {
  int iterations = 100;
  double learning_rate = 1e-4;  // Adam's, on the network's weights
  // After every evaluation: iteration (0 = the network as loaded) and L_p in J.
  std::function<void(int iteration, double potential)> on_iteration;
};

struct PhysicsOptimizationResult {
  // Garment vertices: the model's prediction (as predict gives it: with the
  // push-out of a model that ends in one), the optimised drape. With a
  // push-out the drape optimised is the network's own (Model::forward_network)
  // plus the push-out's correction of the prediction, held fixed: the
  // prediction at the start, moved by the weights as the network's drape is.
  Eigen::MatrixX3d before, after;
  std::vector<EnergyTerm> energies_before, energies_after;  // each effect, J
  double potential_before = 0, potential_after = 0;         // L_p, J
  double penetration_before = 0, penetration_after = 0;     // fraction of garment vertices inside the body
  std::vector<double> history;  // L_p at every iteration, history[0] = before
  int best_iteration = 0;       // the iterate returned as `after` (the lowest L_p seen)
  double seconds = 0;
  // With a barrier in the scene: the shrink of the body that separated the
  // prediction from it (m; 0 when it was already clear), the steps undone
  // because they would have crossed the body (each retried shorter), and whether a drape on the fully grown-back body was
  // reached (`after` is then the best of those, else the last drape, and
  // `unseparated` says why). Always true without a barrier.
  double start_shrink = 0;
  int refused_steps = 0;
  // The iteration at which the shrunk body was back to its true shape (0 when
  // it did not start shrunk, -1 when it never was).
  int grown_iteration = 0;
  bool separated = true;
  std::string unseparated;
  // Empty, or why the optimisation ended before its iterations: an energy or
  // the network failed on a drape the collision checks had let through (the
  // barrier's "touches the body" at distance 0). The drapes before it stand:
  // a best drape on the true body is still a result.
  std::string stopped;
};

// A scene with a barrier (an energy that bounds steps): no accepted drape
// crosses the body, whatever the learning rate. A prediction that crosses the
// body starts against the body shrunk until it is clear (0.5-6 cm), which
// grows back as the barrier pushes the cloth out; only drapes on the true body
// are returned as results (`separated`).
//
// Changes the model's weights in place (Model::load again to undo): they are
// left at the iterate returned as `after`, so the model then predicts it. Runs on
// the calling thread alone (OpenMP set to one thread for the call). `body` holds
// one sample (SampleBatch::body [1, Nb, 3], body_params when the graph takes
// them). ConfigError when the scene's garment is not the model's template
// (another vertex count or other faces); Error when the prediction or an
// energy is not finite before the first step. A failure after it ends this
// optimisation only (`stopped`), so that a caller optimising many drapes
// loses one sample, not the run.
PhysicsOptimizationResult optimize_drape(Model& model, const Simulation& scene, const SampleBatch& body,
                                         const PhysicsOptimizationOptions& options = {});

}  // namespace drape
