// The physics-enforced optimisation (drape/training/physics_optimization.hpp) on the
// tiny T-shirt: the potential falls from the network's prediction, the best
// iterate is returned, the weights change in place, hard starts stay finite,
// a scene of another template is refused, and with a barrier no result
// crosses the body.
#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/training/physics_optimization.hpp>

#include <catch2/catch.hpp>

#include "train_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// The tiny template with every effect, collision included.
Scene tiny_physics_scene(const std::string& collision = "collision: {stiffness: 1.0e8, margin: 0.004}") {
  return parse_scene(std::string("body: {model: parametric}\n"
                                 "garment: {template: tshirt, params: {resolution: 300}}\n"
                                 "effects:\n  gravity: {}\n  stretching: {}\n  bending: {}\n  ") +
                     collision + "\n");
}

struct TinyModel {
  TempDir dir;
  std::filesystem::path file = dir / "model.h5";
  TinyModel() {
    write_tiny_dataset(dir / "data.h5", 12, 8, 2);
    TrainOptions o = tiny_training(dir / "data.h5", file);
    o.epochs = 2;
    train(plugins(), o);
  }
  Model load() const { return Model::load(plugins(), file, assets_cache()); }
};

// The tiny model, the scene with every effect and the body it is optimised
// for: the setting of the tests that follow the potential down.
struct OptimizeCase {
  TinyModel tiny;
  Model model = tiny.load();
  Simulation scene{plugins(), tiny_physics_scene()};
  SampleBatch body = body_of_bmi(40);
  SampleBatch body_of_bmi(double bmi) {
    BodyRequest request;
    request.bmi = bmi;
    return model.body_for(request);
  }
};

}  // namespace

TEST_CASE("optimize_drape lowers the scene's potential from the network's prediction", "[optimize]") {
  OptimizeCase c;
  Model& model = c.model;
  const SampleBatch& body = c.body;
  const Tensor predicted = model.predict(body);

  PhysicsOptimizationOptions o;
  o.iterations = 25;
  o.learning_rate = 1e-3;
  int calls = 0;
  o.on_iteration = [&](int, double) { ++calls; };
  const PhysicsOptimizationResult r = optimize_drape(model, c.scene, body, o);
  CHECK(calls == 26);
  REQUIRE(r.history.size() == 26);
  for (double lp : r.history) CHECK(std::isfinite(lp));
  // The network's own prediction comes first, unchanged.
  CHECK((r.before - predicted.mat(0).cast<double>()).cwiseAbs().maxCoeff() == 0.0);
  CHECK(r.potential_before == r.history.front());
  // The returned drape is the lowest-potential iterate, well below the start.
  CHECK(r.potential_after == *std::min_element(r.history.begin(), r.history.end()));
  CHECK(r.potential_after < 0.9 * r.potential_before);
  CHECK(r.best_iteration > 0);
  REQUIRE(r.energies_after.size() == 4);
  double sum = 0;
  for (const auto& t : r.energies_after) sum += t.value;
  CHECK(sum == Approx(r.potential_after));
  CHECK(r.penetration_after <= r.penetration_before);
  // The weights were fine-tuned in place: the model now predicts something else.
  CHECK((model.predict(body).mat(0) - predicted.mat(0)).cwiseAbs().maxCoeff() > 0.0f);
}

TEST_CASE("optimize_drape leaves the model predicting the drape it returns and not its last iterate", "[optimize]") {
  OptimizeCase c;
  Model& model = c.model;
  const SampleBatch& body = c.body;
  // A learning rate large enough that Adam overshoots: the potential falls,
  // then rises again before the last iteration (its lowest at iteration 10).
  PhysicsOptimizationOptions o;
  o.iterations = 25;
  o.learning_rate = 2.5e-2;
  const PhysicsOptimizationResult r = optimize_drape(model, c.scene, body, o);
  INFO("best iteration " << r.best_iteration << " of " << o.iterations);
  REQUIRE(r.best_iteration > 0);
  REQUIRE(r.best_iteration < o.iterations);
  CHECK(r.history.back() > r.potential_after);
  CHECK((model.predict(body).mat(0).cast<double>() - r.after).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("optimize_drape stays finite from a start deep inside the body, with a 100x stiffer cloth", "[optimize][hard]") {
  TinyModel tiny;
  Model model = tiny.load();
  // A very heavy body: the template, predicted for it, starts centimetres inside.
  BodyRequest request;
  request.bmi = 65;
  const SampleBatch body = model.body_for(request);
  const Simulation stiff(plugins(), parse_scene("body: {model: parametric}\n"
                                               "garment: {template: tshirt, params: {resolution: 300}}\n"
                                               "materials: {knit: {base: gray-interlock-linear, multipliers: {stretch: 100, bend: 100}}}\n"
                                               "effects:\n  gravity: {}\n  stretching: {}\n  bending: {}\n"
                                               "  collision: {stiffness: 1.0e8, margin: 0.004}\n"));
  PhysicsOptimizationOptions o;
  o.iterations = 20;
  o.learning_rate = 1e-3;
  const PhysicsOptimizationResult r = optimize_drape(model, stiff, body, o);
  CHECK(r.penetration_before > 0.05);  // a genuinely hard start
  for (double lp : r.history) CHECK(std::isfinite(lp));
  CHECK(r.after.allFinite());
  CHECK(r.potential_after < r.potential_before);
  CHECK(r.penetration_after < r.penetration_before);
}

TEST_CASE("optimize_drape refuses a scene of another template and bad settings", "[optimize]") {
  TinyModel tiny;
  Model model = tiny.load();
  const SampleBatch body = model.body_for(BodyRequest{});
  const Simulation other(plugins(), parse_scene("body: {model: parametric}\n"
                                               "garment: {template: tshirt, params: {resolution: 400}}\n"
                                               "effects: [gravity]\n"));
  CHECK_THROWS_WITH(optimize_drape(model, other, body), Catch::Contains("not the template the model was trained on"));
  const Simulation scene(plugins(), tiny_physics_scene());
  PhysicsOptimizationOptions bad;
  bad.learning_rate = 0;
  CHECK_THROWS_AS(optimize_drape(model, scene, body, bad), ConfigError);
  SampleBatch two;
  two.body = Tensor(2, body.body.rows(), 3);
  CHECK_THROWS_WITH(optimize_drape(model, scene, two), Catch::Contains("one body at a time"));
}

namespace {

// Separated from the body, by tools that share no code with the contact: the
// exact crossing count and the signed distance of every vertex.
bool clear_of_body(const Eigen::MatrixX3d& garment, const Mesh& template_mesh, const SampleBatch& body, const Model& model) {
  const Eigen::MatrixX3d b = body.body.mat(0).cast<double>();
  const geometry::SurfaceCrossings c = geometry::surface_crossings(garment, template_mesh.faces, b, model.assets().body.faces);
  return c.total() == 0 && geometry::penetration_ratio(geometry::BodySurface(b, model.assets().body.faces), garment) == 0;
}

}  // namespace

TEST_CASE("optimize_drape with a barrier ends clear of the body whatever the learning rate", "[optimize][barrier]") {
  TinyModel tiny;
  BodyRequest request;
  request.bmi = 27;  // the prediction starts a little inside this body
  const std::string barrier = "barrier: {}", both = "barrier: {}\n  collision: {stiffness: 1.0e10, margin: 0.004, smoothing: 0.02}";
  for (const auto& [contact, lr] : {std::pair{barrier, 1e-2}, std::pair{barrier, 1.0}, std::pair{both, 1e-2}}) {
    const Simulation scene(plugins(), tiny_physics_scene(contact));
    Model model = tiny.load();
    const SampleBatch body = model.body_for(request);
    PhysicsOptimizationOptions o;
    o.iterations = 100;
    o.learning_rate = lr;
    const PhysicsOptimizationResult r = optimize_drape(model, scene, body, o);
    INFO(contact << ", learning rate " << lr << ": start shrink " << r.start_shrink << " m, " << r.refused_steps
                 << " steps refused; " << r.unseparated);
    CHECK_FALSE(clear_of_body(r.before, scene.garment().mesh, body, model));  // a genuinely crossing start
    CHECK(r.start_shrink > 0);
    REQUIRE(r.separated);
    CHECK(clear_of_body(r.after, scene.garment().mesh, body, model));
    CHECK(r.best_iteration > 0);
    // The body was back before the best drape, which is only taken on it.
    CHECK(r.grown_iteration > 0);
    CHECK(r.grown_iteration <= r.best_iteration);
    CHECK(std::find_if(r.energies_after.begin(), r.energies_after.end(),
                       [](const EnergyTerm& t) { return t.name == "barrier"; }) != r.energies_after.end());
    for (double lp : r.history) CHECK(std::isfinite(lp));
    // With Adam's steps 100x too long the collision checks had to undo some.
    if (lr > 0.5) CHECK(r.refused_steps > 0);
  }
}

namespace {

// An energy of nothing that fails from its n-th gradient on, as the barrier
// does when rounding has let a pair reach distance 0: a failure on a drape the
// collision checks accepted.
class FailsAfter final : public Energy {
 public:
  explicit FailsAfter(int calls) : calls_left_(calls) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d&) const override { return 0; }
  double add_gradient(const Eigen::MatrixX3d&, Eigen::MatrixX3d&) const override {
    if (calls_left_-- <= 0) throw Error("test: garment vertex 7 touches the body (distance 0)");
    return 0;
  }
  void add_hessian(const Eigen::MatrixX3d&, Triplets&, bool) const override {}

 private:
  mutable int calls_left_;
};

// The shipped plugins and `fails_after`.
Registry& plugins_with_a_failing_energy() {
  static Registry* r = [] {
    auto* reg = new Registry;  // kept for the run, as plugins() is
    reg->load_path({test::plugin_dir().string()});
    PluginDescriptor d;
    d.kind = "energy";
    d.name = "fails_after";
    d.doc = "test: throws from the given gradient call on";
    d.params = {{"calls", ParamType::Int, "1", "gradient calls that succeed", 0.0}};
    d.create_energy = [](const Params& p) { return std::make_unique<FailsAfter>(static_cast<int>(p.get_int("calls"))); };
    reg->add(d);
    return reg;
  }();
  return *r;
}

}  // namespace

TEST_CASE("a failure in the middle of optimize_drape ends that optimisation only and keeps the drapes before it",
          "[optimize][barrier]") {
  // drape optimize --data runs hundreds of these: one failure must cost one
  // sample, not the run (it used to rethrow and stop every worker).
  TinyModel tiny;
  const Registry& registry = plugins_with_a_failing_energy();
  BodyRequest request;
  request.bmi = 27;  // the prediction starts a little inside: the barrier's body starts shrunk
  for (const int calls : {2, 90}) {
    const Simulation scene(registry, tiny_physics_scene("barrier: {}\n  fails_after: {calls: " + std::to_string(calls) + "}"));
    Model model = Model::load(registry, tiny.file, assets_cache());
    const SampleBatch body = model.body_for(request);
    PhysicsOptimizationOptions o;
    o.iterations = 100;
    o.learning_rate = 1e-2;
    PhysicsOptimizationResult r;
    REQUIRE_NOTHROW(r = optimize_drape(model, scene, body, o));
    INFO("calls " << calls << ": " << r.stopped << "; grown at " << r.grown_iteration << ", best " << r.best_iteration);
    CHECK_THAT(r.stopped, Catch::Contains("touches the body"));
    // One gradient for the prediction, one against the shrunk body, then one per drape.
    CHECK(static_cast<int>(r.history.size()) == calls - 1);
    for (double lp : r.history) CHECK(std::isfinite(lp));
    CHECK(r.after.allFinite());
    // The model predicts the drape returned, not the step that failed.
    CHECK((model.predict(body).mat(0).cast<double>() - r.after).cwiseAbs().maxCoeff() == 0.0);
    if (calls == 2) {
      // Stopped before the body was back: not a result, and it says why.
      CHECK_FALSE(r.separated);
      CHECK_THAT(r.unseparated, Catch::Contains("stopped after iteration 0"));
    } else {
      // Stopped after it: the best drape on the true body stands.
      REQUIRE(r.grown_iteration > 0);
      CHECK(r.separated);
      CHECK(r.best_iteration >= r.grown_iteration);
      CHECK(clear_of_body(r.after, scene.garment().mesh, body, model));
    }
  }
}
