// A plugin writes plain messages; the framework names the plugin at the calls
// it makes into it (error_context.hpp): factories, every energy method, a
// garment's build, and warnings given meanwhile. The kind of error is kept and
// a message that already names the plugin is not named twice.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/energy.hpp>
#include <drape/error_context.hpp>
#include <drape/errors.hpp>
#include <drape/registry.hpp>
#include <drape/warnings.hpp>

#include <string>
#include <vector>

using namespace drape;

namespace {

// An energy whose every call fails in its own plain words.
class Grumpy final : public Energy {
 public:
  void bind(const EnergyContext&) override {
    warn("the garment looks odd");
    throw ConfigError("needs a garment it likes");
  }
  double value(const Eigen::MatrixX3d&) const override { throw Error("value is undefined"); }
  double add_gradient(const Eigen::MatrixX3d&, Eigen::MatrixX3d&) const override {
    throw UsageError("grumpy: already named");
  }
  void add_hessian(const Eigen::MatrixX3d&, Triplets&, bool) const override { throw std::bad_alloc(); }
  double max_step(const Eigen::MatrixX3d&, const Eigen::MatrixX3d&, const Eigen::MatrixX3d*,
                  const Eigen::MatrixX3d*) const override {
    return std::vector<double>().at(3);  // a standard library's error, not drape's
  }
};

class GrumpyGarment final : public GarmentSource {
 public:
  Garment build() const override { throw ConfigError("no pattern"); }
};

void add_grumpy_plugins(Registry& registry, bool factory_fails) {
  PluginDescriptor energy;
  energy.kind = "energy";
  energy.name = "grumpy";
  energy.create_energy = [factory_fails](const Params&) -> std::unique_ptr<Energy> {
    if (factory_fails) throw ConfigError("parameter 'mood' is out of range");
    return std::make_unique<Grumpy>();
  };
  registry.add(energy);
  PluginDescriptor garment;
  garment.kind = "garment";
  garment.name = "sulky";
  garment.create_garment = [](const Params&) { return std::make_unique<GrumpyGarment>(); };
  registry.add(garment);
}

template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace

TEST_CASE("a plugin's errors and warnings name the plugin once", "[registry]") {
  Registry registry;
  add_grumpy_plugins(registry, false);
  auto energy = registry.create_energy("grumpy", Params());
  std::vector<std::string> warnings;
  const WarningHandler previous = set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  CHECK_THROWS_AS(energy->bind(EnergyContext()), ConfigError);
  set_warning_handler(previous);
  CHECK(warnings == std::vector<std::string>{"grumpy: the garment looks odd"});
  CHECK(message_of([&] { energy->bind(EnergyContext()); }) == "grumpy: needs a garment it likes");

  const Eigen::MatrixX3d x = Eigen::MatrixX3d::Zero(1, 3);
  CHECK(message_of([&] { energy->value(x); }) == "grumpy: value is undefined");
  Eigen::MatrixX3d g = x;
  CHECK_THROWS_AS(energy->add_gradient(x, g), UsageError);  // the kind is kept
  CHECK(message_of([&] { energy->add_gradient(x, g); }) == "grumpy: already named");
  Triplets h;
  CHECK_THROWS_AS(energy->add_hessian(x, h, true), std::bad_alloc);  // out of memory: passed on as it is
  // Any other exception becomes a drape Error that says whose it was.
  CHECK_THROWS_AS(energy->max_step(x, x, nullptr, nullptr), Error);
  CHECK_THAT(message_of([&] { energy->max_step(x, x, nullptr, nullptr); }),
             Catch::StartsWith("grumpy: ") && Catch::Contains("vector"));

  auto garment = registry.create_garment("sulky", Params());
  CHECK(message_of([&] { garment->build(); }) == "sulky: no pattern");
  CHECK(current_context() == nullptr);  // no name is left behind after a plugin's call
}

TEST_CASE("a factory's refusal names the plugin", "[registry]") {
  Registry registry;
  add_grumpy_plugins(registry, true);
  CHECK_THROWS_AS(registry.create_energy("grumpy", Params()), ConfigError);
  CHECK(message_of([&] { registry.create_energy("grumpy", Params()); }) ==
        "grumpy: parameter 'mood' is out of range");
}

TEST_CASE("with_context adds a name only where it is missing", "[registry]") {
  CHECK(with_context("edge", "backward without a forward") == "edge: backward without a forward");
  CHECK(with_context("edge", "edge: backward without a forward") == "edge: backward without a forward");
  CHECK(with_context("edge", "edge needs a template") == "edge needs a template");
  CHECK(with_context("edge", "edges are missing") == "edge: edges are missing");  // a longer word is not the name
}
