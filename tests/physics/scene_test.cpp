// Scene files: base chains, overrides, removal, and errors that name file:line.
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;
using namespace drape::test;

namespace {

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kBase = R"(description: base
body:
  model: parametric
  shape: {bmi: 30, height: 1.8}
garment:
  template: tshirt
  params: {resolution: coarse}
materials:
  knit: gray-interlock
effects: [gravity, stretching, bending, collision]
solver: {time_step: 0.05, morph_steps: 10}
)";

}  // namespace

TEST_CASE("a scene reads body, garment, materials, effects and solver", "[scene]") {
  const Scene s = parse_scene(kBase, "base.yaml");
  CHECK(s.description == "base");
  CHECK(s.body_model == "parametric");
  CHECK(s.shape.at("bmi").node.as<double>() == 30);
  CHECK(s.shape.at("height").where.line == 4);
  CHECK(s.garment == "tshirt");
  CHECK(s.garment_params.at("resolution").node.as<std::string>() == "coarse");
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].region == "knit");
  REQUIRE(s.effects.size() == 4);
  CHECK(s.effects[3].name == "collision");
  CHECK(s.has_effect("bending"));
  CHECK_FALSE(s.has_effect("wind"));
  CHECK(s.solver.at("morph_steps").node.as<int>() == 10);
}

TEST_CASE("a derived scene overrides single entries and removes effects with null", "[scene]") {
  TempDir dir;
  write(dir / "base.yaml", kBase);
  write(dir / "derived.yaml", R"(base: base.yaml
body: {shape: {bmi: 65}}
garment: {params: {print: true}}
materials: {print: {base: screen-print, multipliers: {stretch: 100}}}
effects: {collision: null, bending: {stiffness_scale: 2}}
solver: {morph_steps: 0}
)");
  const Scene s = load_scene(dir / "derived.yaml");
  CHECK(s.shape.at("bmi").node.as<double>() == 65);
  CHECK(s.shape.at("bmi").where.file == (dir / "derived.yaml").string());
  CHECK(s.shape.at("height").node.as<double>() == 1.8);  // kept from the base
  CHECK(s.garment_params.size() == 2);
  CHECK(s.materials.size() == 2);
  REQUIRE(s.effects.size() == 3);
  CHECK_FALSE(s.has_effect("collision"));
  CHECK(s.effects[2].name == "bending");
  CHECK(s.effects[2].params.at("stiffness_scale").node.as<double>() == 2);
  CHECK(s.solver.at("morph_steps").node.as<int>() == 0);
  CHECK(s.solver.at("time_step").node.as<double>() == 0.05);
  // The resolved text has no base and reads back to the same scene.
  const Scene again = parse_scene(s.yaml());
  CHECK(again.effects.size() == 3);
  CHECK(again.shape.at("bmi").node.as<double>() == 65);
  CHECK(again.materials.size() == 2);
  // Removing an effect the scene does not have (a misspelling) is refused:
  // it left the effect running without a word.
  write(dir / "typo.yaml", "base: base.yaml\neffects: {colision: null}\n");
  CHECK_THAT(message_of([&] { load_scene(dir / "typo.yaml"); }),
             Catch::Contains("typo.yaml:2") && Catch::Contains("removes effect 'colision', which the scene does not have") &&
                 Catch::Contains("did you mean 'collision'"));
}

TEST_CASE("an effects list in a derived scene replaces the base's", "[scene]") {
  TempDir dir;
  write(dir / "base.yaml", kBase);
  write(dir / "d.yaml", "base: base.yaml\neffects: [gravity]\n");
  const Scene s = load_scene(dir / "d.yaml");
  REQUIRE(s.effects.size() == 1);
  CHECK(s.effects[0].name == "gravity");
}

TEST_CASE("scene errors name the file, the line and the key", "[scene]") {
  CHECK_THAT(message_of([] { parse_scene("body: {model: parametric}\neffect: [gravity]\n", "s.yaml"); }),
             Catch::Contains("s.yaml:2") && Catch::Contains("unknown key 'effect'") && Catch::Contains("effects"));
  CHECK_THAT(message_of([] { parse_scene("body: {modle: parametric}\n", "s.yaml"); }),
             Catch::Contains("s.yaml:1") && Catch::Contains("'modle'") && Catch::Contains("model"));
  CHECK_THAT(message_of([] { parse_scene("effects: [gravity\n", "s.yaml"); }),
             Catch::Contains("s.yaml") && Catch::Contains("malformed YAML"));
  CHECK_THAT(message_of([] { parse_scene("effects: 3\n", "s.yaml"); }), Catch::Contains("s.yaml:1"));
  // yaml-cpp alone keeps one of two equal keys: the second garment would be lost without a word.
  CHECK_THAT(message_of([] { parse_scene("garment: {template: tshirt}\nbody: {}\ngarment: {grade: 1.2}\n", "s.yaml"); }),
             Catch::Contains("s.yaml:3") && Catch::Contains("'garment' is defined twice") && Catch::Contains("line 1"));
  // An anchor used inside the node it names is an endless tree: every walk of
  // it (this check first) recursed until the stack overflowed.
  CHECK_THAT(message_of([] { parse_scene("a: &x [*x]\n", "s.yaml"); }),
             Catch::Contains("s.yaml:1") && Catch::Contains("recursive alias"));
  CHECK_THAT(message_of([] { parse_scene("body: {model: parametric}\nsolver: &s {inner: *s}\n", "s.yaml"); }),
             Catch::Contains("s.yaml:2") && Catch::Contains("recursive alias"));
  // A file cut in the middle of a key: yaml-cpp reads the bare word as a key
  // with no value, which a scene takes for "reset it to the base's".
  CHECK_THAT(message_of([] { parse_scene("body: {model: parametric}\nsolver:\n  time_step: 0.1\n  morph\n", "s.yaml"); }),
             Catch::Contains("s.yaml:4") && Catch::Contains("'morph' has no value"));
  // A folded description over two lines is YAML, and kept.
  CHECK_THAT(message_of([] { parse_scene("description: a long\n  story\nbody: {model: parametric}\n", "s.yaml"); }),
             !Catch::Contains("has no value"));
  // Aliases of aliases, nine deep and nine wide (a "billion laughs"): 9^9
  // nodes once expanded, and every walk of them hung; refused at once.
  {
    std::string laughs = "l0: &l0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
    for (int level = 1; level <= 9; ++level) {
      const std::string below = "*l" + std::to_string(level - 1);
      laughs += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " [" + below;
      for (int k = 1; k < 9; ++k) laughs += ", " + below;
      laughs += "]\n";
    }
    CHECK_THAT(message_of([&] { parse_scene(laughs, "s.yaml"); }),
               Catch::Contains("s.yaml:") && Catch::Contains("more than 200000 YAML nodes once its aliases"));
  }
  // An alias used twice side by side is no recursion.
  CHECK_THAT(message_of([] { parse_scene("x: &g [gravity]\neffects: *g\n", "s.yaml"); }),
             !Catch::Contains("recursive alias"));
  CHECK_THAT(message_of([] { parse_scene("solver:\n  time_step: 0.1\n  time_step: 0.2\n", "s.yaml"); }),
             Catch::Contains("s.yaml:3") && Catch::Contains("'time_step'"));
  // A solver setting among the effects is named as one (it read "effect 'morph_steps' must be a map").
  CHECK_THAT(message_of([] { parse_scene("effects:\n  gravity: {}\n  morph_steps: 4\n", "s.yaml"); }),
             Catch::Contains("s.yaml:3") && Catch::Contains("'morph_steps' is a solver setting") && Catch::Contains("solver:"));
  CHECK_THAT(message_of([] { parse_scene("effects: [gravity, {settle_steps: 4}]\n", "s.yaml"); }),
             Catch::Contains("'settle_steps' is a solver setting"));
  // An effect listed twice was merged without a word (the map form's key twice is refused above).
  CHECK_THAT(message_of([] { parse_scene("effects: [gravity, stretching, gravity]\n", "s.yaml"); }),
             Catch::Contains("s.yaml:1") && Catch::Contains("effect 'gravity' is listed twice (first at line 1)"));
  CHECK_THAT(message_of([] { parse_scene("effects:\n  - gravity\n  - {gravity: {g: 5}}\n", "s.yaml"); }),
             Catch::Contains("s.yaml:3") && Catch::Contains("listed twice (first at line 2)"));
  // `effects:` with nothing under it kept the base's effects unseen.
  CHECK_THAT(message_of([] { parse_scene("body: {model: parametric}\neffects:\n", "s.yaml"); }),
             Catch::Contains("s.yaml:2") && Catch::Contains("`effects` has nothing under it"));
  TempDir dir;
  write(dir / "a.yaml", "base: b.yaml\n");
  write(dir / "b.yaml", "base: a.yaml\n");
  CHECK_THAT(message_of([&] { load_scene(dir / "a.yaml"); }), Catch::Contains("loops back"));
  CHECK_THAT(message_of([&] { load_scene(dir / "missing.yaml"); }), Catch::Contains("does not exist"));
  // A user's scene elsewhere names a shipped one by its path in the source
  // tree or by its name among the shipped scenes (it said "base scene ...
  // does not exist"); one found nowhere names where it was looked for.
  write(dir / "by_path.yaml", "base: graphs/scenes/tshirt_coarse.yaml\nbody: {shape: {bmi: 31}}\n");
  write(dir / "by_name.yaml", "base: tshirt_coarse.yaml\nbody: {shape: {bmi: 31}}\n");
  const Scene shipped = load_scene(test::source_dir() / "graphs/scenes/tshirt_coarse.yaml");
  for (const char* name : {"by_path.yaml", "by_name.yaml"}) {
    INFO(name);
    const Scene s = load_scene(dir / name);
    CHECK(s.shape.at("bmi").node.as<double>() == 31);
    CHECK(s.effects.size() == shipped.effects.size());
    CHECK(s.garment_params.at("resolution").node.as<std::string>() ==
          shipped.garment_params.at("resolution").node.as<std::string>());
  }
  write(dir / "nowhere.yaml", "base: no_such_scene.yaml\n");
  CHECK_THAT(message_of([&] { load_scene(dir / "nowhere.yaml"); }),
             Catch::Contains("nowhere.yaml:1") && Catch::Contains("base scene 'no_such_scene.yaml' does not exist (looked in " +
                                                                   dir.path().string()) &&
                 Catch::Contains("graphs/scenes"));
}

TEST_CASE("a misspelt effect is refused with the list of known effects", "[scene]") {
  const Scene s = parse_scene("effects: [gravity, gravty]\n", "s.yaml");
  const std::string m = message_of([&] { validate_scene(s, plugins()); });
  CHECK_THAT(m, Catch::Contains("s.yaml:1") && Catch::Contains("unknown effect 'gravty'") &&
                    Catch::Contains("did you mean 'gravity'") && Catch::Contains("known effects: "));
  // Other kinds of plugin are not effects.
  CHECK_THAT(message_of([&] { validate_scene(parse_scene("effects: [mlp]\n", "s.yaml"), plugins()); }),
             Catch::Contains("unknown effect 'mlp'"));
  CHECK_THAT(message_of([&] { validate_scene(parse_scene("effects: []\n", "s.yaml"), plugins()); }),
             Catch::Contains("no effects"));
  CHECK_THAT(message_of([&] { validate_scene(parse_scene("effects: [gravity]\nsolver: {time_stp: 1}\n", "s.yaml"), plugins()); }),
             Catch::Contains("time_stp") && Catch::Contains("time_step"));
  CHECK_THAT(message_of([&] { validate_scene(parse_scene("effects: {gravity: {g: -1}}\n", "s.yaml"), plugins()); }),
             Catch::Contains("'g'") && Catch::Contains("s.yaml:1"));
  CHECK_NOTHROW(validate_scene(parse_scene("effects: [gravity]\n", "s.yaml"), plugins()));
  // The preconditioner's precision is one of two words.
  CHECK_THAT(message_of([&] { validate_scene(parse_scene("effects: [gravity]\nsolver: {preconditioner: half}\n", "s.yaml"), plugins()); }),
             Catch::Contains("'half'") && Catch::Contains("float") && Catch::Contains("double"));
  CHECK_NOTHROW(validate_scene(parse_scene("effects: [gravity]\nsolver: {preconditioner: double}\n", "s.yaml"), plugins()));
}

TEST_CASE("a garment plugin's own check of its parameters names the scene's file and line", "[scene]") {
  // The T-shirt checks its resolution when it is made: its message knew no file.
  const Scene s = parse_scene("body: {model: parametric}\ngarment:\n  template: tshirt\n  params: {resolution: ultra}\n"
                              "effects: [gravity]\n",
                              "s.yaml");
  CHECK_THAT(message_of([&] { Simulation(plugins(), s); }),
             Catch::Contains("s.yaml:4") && Catch::Contains("resolution 'ultra'"));
}

TEST_CASE("the shipped scenes are valid", "[scene]") {
  int scenes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_dir() / "graphs" / "scenes")) {
    if (!entry.is_regular_file() || entry.path().extension() != ".yaml") continue;
    ++scenes;
    INFO(entry.path());
    const Scene s = load_scene(entry.path());
    CHECK_NOTHROW(validate_scene(s, plugins()));
  }
  CHECK(scenes >= 14);  // graphs/scenes and the earlier solvers' scenes in its folders
}
