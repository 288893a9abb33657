// The drape program as a user meets it: exit codes and one-line errors.
#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;

TEST_CASE("drape plugins lists plugins with kind, ports and parameters", "[cli]") {
  std::string out;
  REQUIRE(test::run_drape("plugins", out) == 0);
  CHECK_THAT(out, Catch::Contains("loss l2") && Catch::Contains("in   pred") && Catch::Contains("param factor"));
  REQUIRE(test::run_drape("plugins --kind op --brief", out) == 0);
  CHECK_THAT(out, Catch::Contains("op add"));
  CHECK(out.find("loss l2") == std::string::npos);
  CHECK(test::run_drape("plugins --kind nosuchkind", out) == 2);
  // A kind in capitals is the kind; a misspelt one is answered with the kinds there are.
  REQUIRE(test::run_drape("plugins --kind Loss --brief", out) == 0);
  CHECK_THAT(out, Catch::Contains("loss l2"));
  CHECK(test::run_drape("plugins --kind lose", out) == 2);
  CHECK_THAT(out, Catch::Contains("did you mean 'loss'") && Catch::Contains("kinds: ") && Catch::Contains("energy"));
}

TEST_CASE("drape graph check validates a shipped graph", "[cli]") {
  std::string out;
  const auto graph = (test::source_dir() / "graphs/examples/residual.yaml").string();
  REQUIRE(test::run_drape("graph check " + graph + " --no-assets --dim garment_vertices=10", out) == 0);
  CHECK_THAT(out, Catch::Contains(": ok") && Catch::Contains("[10, 3]"));
}

TEST_CASE("configuration errors exit 2 with file, line and close matches", "[cli]") {
  test::TempDir dir;
  std::string out;
  std::ofstream(dir / "broken.yaml") << "inputs: { x: [4, 3] }\nnodes:\n  a: { type: scale, in: [x }\n";
  CHECK(test::run_drape("graph check --no-assets " + (dir / "broken.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("broken.yaml:3") && Catch::Contains("malformed YAML"));

  std::ofstream(dir / "typo.yaml") << "inputs: { x: [4, 3] }\nnodes:\n  a: { type: scal, in: x }\noutputs: [a]\n";
  CHECK(test::run_drape("graph check --no-assets " + (dir / "typo.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("typo.yaml:3") && Catch::Contains("unknown plugin type 'scal'") &&
                      Catch::Contains("did you mean 'scale'"));

  CHECK(test::run_drape("graph check --no-assets " + (dir / "missing.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("missing.yaml"));
  CHECK(test::run_drape("graph check --no-assets " + dir.path().string(), out) == 2);  // a folder (it was "not a YAML map")
  CHECK_THAT(out, Catch::Contains("is a folder, not a YAML file"));

  // A scene's body model and garment template named at their lines (an outside check: the file only).
  std::ofstream(dir / "body.yaml") << "effects: [gravity]\nbody: {model: parametrik}\n";
  CHECK(test::run_drape("simulate " + (dir / "body.yaml").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("body.yaml:2: unknown body model 'parametrik'; did you mean 'parametric'"));
  std::ofstream(dir / "garment.yaml") << "effects: [gravity]\n\ngarment: {template: tshrit}\n";
  CHECK(test::run_drape("simulate " + (dir / "garment.yaml").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("garment.yaml:3: unknown garment template 'tshrit'; did you mean 'tshirt'"));
  // A flow left open is named on the file's last line, not the one after it;
  // an empty scene as empty, not as a scene without effects.
  std::ofstream(dir / "open.yaml") << "effects: [gravity]\nsolver: {morph_steps: 2\n";
  CHECK(test::run_drape("simulate " + (dir / "open.yaml").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("open.yaml:2: malformed YAML") && Catch::Contains("(at the end of the file)"));
  std::ofstream(dir / "empty.yaml") << "# nothing yet\n";
  CHECK(test::run_drape("simulate " + (dir / "empty.yaml").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("empty.yaml: the file is empty (or only comments)"));
  // A tab in the indentation is named (yaml-cpp says "illegal map value").
  std::ofstream(dir / "tab.yaml") << "effects: [gravity]\nbody:\n\tshape: {bmi: 30}\n";
  CHECK(test::run_drape("simulate " + (dir / "tab.yaml").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("tab.yaml:3: malformed YAML") &&
                      Catch::Contains("(line 3 is indented with a tab: YAML indents with spaces only)"));
}

// The human rig's graphs read the body resampled onto the mannequin's
// vertices: graph check takes the encoder body and the rig as train does
// (they could not be checked: "the template assets name no encoder body").
TEST_CASE("graph check checks the human rig's graphs with --encoder-body and --body-param", "[cli]") {
  std::string out;
  const std::string graph = "graph check graphs/human/drape_grade_v2v1000_post_resampled.yaml --resolution coarse";
  CHECK(test::run_drape(graph, out) == 2);
  CHECK_THAT(out, Catch::Contains("give --encoder-body"));
  REQUIRE(test::run_drape(graph + " --encoder-body parametric --body-param rig=human", out) == 0);
  CHECK_THAT(out, Catch::Contains(": ok") && Catch::Contains("input  body [6904, 3]"));
  CHECK(test::run_drape(graph + " --encoder-body parametric --body-param rig", out) == 2);
  CHECK_THAT(out, Catch::Contains("--body-param 'rig': expected name=value"));
}

TEST_CASE("usage errors exit 2, help exits 0", "[cli]") {
  std::string out;
  CHECK(test::run_drape("plugnis", out) == 2);
  CHECK_THAT(out, Catch::Contains("did you mean 'plugins'"));
  CHECK(test::run_drape("plugins --no-such-flag", out) == 2);
  CHECK_THAT(out, Catch::StartsWith("drape plugins: error: "));  // as a ConfigError is said (it had no "error:")
  CHECK(test::run_drape("graph", out) == 2);
  CHECK(test::run_drape("graph check --help", out) == 0);
  CHECK_THAT(out, Catch::Contains("usage: drape graph check"));
  CHECK(test::run_drape("--help", out) == 0);
  CHECK_THAT(out, Catch::Contains("plugins") && Catch::Contains("graph"));
  // NaN is no number (it was told "a range needs --sample": NaN != NaN).
  for (const char* bad : {"--bmi nan", "--height nan", "--bmi 20:nan"}) {
    INFO(bad);
    CHECK(test::run_drape(std::string("body ") + bad + " --out x.obj", out) == 2);
    CHECK_THAT(out, Catch::Contains("': not a number (NaN)"));
  }
  for (const char* command : {"predict --bmi nan --out x.obj", "optimize --scene graphs/scenes/tshirt_coarse.yaml --bmi nan --out x.obj",
                              "predict --bmi 30 --height nan --out x.obj"}) {
    INFO(command);
    CHECK(test::run_drape(command, out) == 2);
    CHECK_THAT(out, Catch::Contains(": not a finite number"));  // (it was "BMI nan is outside the reachable range")
  }
  CHECK(test::run_drape("plugnis", out) == 2);
  CHECK_THAT(out, Catch::StartsWith("drape: error: unknown command 'plugnis'"));
  CHECK(test::run_drape("body --bmi inf --out x.obj", out) == 2);
  CHECK_THAT(out, Catch::Contains("--bmi 'inf': expected a finite number or a range lo:hi"));
}

TEST_CASE("drape graph check takes sizes and the garment from the template's assets", "[cli]") {
  test::TempDir cache;
  std::string out;
  const auto graph = (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string();
  const std::string cmd = "env DRAPE_CACHE_DIR=" + cache.path().string() + " " + test::drape_program().string() +
                          " graph check " + graph + " --resolution coarse --k 16";
  REQUIRE(test::run(cmd, out) == 0);
  CHECK_THAT(out, Catch::Contains("input  body [6490, 3]") && Catch::Contains("out out [") && Catch::Contains("loss   edge"));
  // Without a template the symbolic sizes are unknown: a configuration error.
  CHECK(test::run_drape("graph check " + graph + " --no-assets", out) == 2);
  CHECK_THAT(out, Catch::Contains("unknown size 'body_vertices'"));

  // It agrees with drape train (an outside check found three graphs "ok" here that train refused or took):
  // an input drape does not feed is refused; body_params, which train sizes from its dataset, is sized
  // from the template's body model; a graph with no loss to train with is said.
  const std::string text = test::read_file(graph);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    const std::size_t at = changed.find(from);
    REQUIRE(at != std::string::npos);
    return changed.replace(at, from.size(), to);
  };
  const std::string check = "env DRAPE_CACHE_DIR=" + cache.path().string() + " " + test::drape_program().string() +
                            " graph check --resolution coarse --k 16 ";
  std::ofstream(cache / "extra.yaml") << with("inputs:\n", "inputs:\n  extra: [5, 3]\n");
  CHECK(test::run(check + (cache / "extra.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("graph input 'extra' is not one drape feeds"));
  std::ofstream(cache / "params.yaml") << with("inputs:\n", "inputs:\n  body_params: [1, body_params]\n");
  REQUIRE(test::run(check + (cache / "params.yaml").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("input  body_params [1, 9]"));  // the mannequin's 9 shape parameters
  std::string zero = with("edge: 0.1", "edge: 0");
  zero.replace(zero.find("l2: 1.0"), 7, "l2: 0");
  std::ofstream(cache / "zero.yaml") << zero;
  REQUIRE(test::run(check + (cache / "zero.yaml").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("note: no loss has a weight above 0, so drape train refuses this graph"));
  REQUIRE(test::run(cmd, out) == 0);
  CHECK_THAT(out, !Catch::Contains("note: no loss"));
}

TEST_CASE("a mistyped flag is refused with the command's closest flags", "[cli]") {
  std::string out;
  CHECK(test::run_drape("predict --bmii 30 --out g.obj", out) == 2);
  CHECK_THAT(out, Catch::Contains("unrecognised option '--bmii'") && Catch::Contains("did you mean --bmi?"));
  CHECK(test::run_drape("generate --count 2 --threds 2 --out d.h5", out) == 2);
  CHECK_THAT(out, Catch::Contains("did you mean --threads?"));
  CHECK(test::run_drape("predict --zzzzzz 1", out) == 2);
  CHECK_THAT(out, !Catch::Contains("did you mean"));  // nothing close: no guess
}

// predict --push-out does what the shipped models' push-out does: the
// vertices, the edges and the faces off the body's peaks. It left "6 body
// edges through the garment" of a BMI 35 body (the faces were not given),
// and the warning then suggested --push-out, which was given (an outside
// check). The crossings are counted by exact edge-triangle tests that share
// no code with the push-out.
TEST_CASE("predict --push-out clears the garment of the body's edges too", "[cli]") {
  test::TempDir dir;
  std::string out;
  for (const char* bmi : {"35", "55"}) {
    INFO(bmi);
    REQUIRE(test::run_drape(std::string("predict --bmi ") + bmi + " --set post.enabled=false --push-out --out " +
                                (dir / "g.obj").string(),
                            out) == 0);
    CHECK_THAT(out, Catch::Contains("p = 0.00% of them inside the body, 0 edges crossing it"));
    CHECK(out.find("--push-out moves the garment off the body") == std::string::npos);
  }
  // And off itself, as the models' push-out untangles: a posed heavy body's
  // shirt was left crossing itself at 13 edge-face pairs (counted by
  // self_edge_crossings, which shares no code with the untangle's search).
  REQUIRE(test::run_drape("predict --set post.enabled=false --bmi 50 --sex 1 --pose shoulder_abduction=30,elbow_flexion=60 "
                          "--push-out --out " + (dir / "p.obj").string(),
                          out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("0 edges crossing it, the garment through itself 0 edge-face pairs"));
}
