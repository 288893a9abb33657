// Scenes on posed bodies (issue 55, item 3): `body: {pose: ...}` read with its
// lines and refused at them, the body's path into the pose (shape morph and
// joint angles together, or one first) from the start body to the posed
// target, and a posed drape that settles with the cloth off the body and off
// itself, counted by tests that share no code with the contact.
#include <drape/bodies/pose.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/scene_pose.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/scene_body.hpp>

#include <catch2/catch.hpp>

#include "posed_scene_text.hpp"
#include "test_support.hpp"

using namespace drape;
using namespace drape::test;

namespace {

const char* kPosed = R"(body:
  model: parametric
  shape: {bmi: 30, height: 1.7, sex: 0}
  pose: {shoulder_abduction: 20, left_elbow_flexion: 45}
garment: {template: tshirt, params: {resolution: 300}}
effects: [gravity, stretching, bending, barrier]
solver: {morph_steps: 4, settle_steps: 2}
)";

std::string scene_error(const std::string& pose_line) {
  std::string text = kPosed;
  text.replace(text.find("  pose: {shoulder_abduction: 20, left_elbow_flexion: 45}"),
               std::string("  pose: {shoulder_abduction: 20, left_elbow_flexion: 45}").size(), pose_line);
  return message_of([&] { Simulation(plugins(), parse_scene(text, "posed.yaml")); });
}

}  // namespace

TEST_CASE("a scene's pose is read with its lines and written back only when set", "[scene][pose]") {
  const Scene s = parse_scene(kPosed, "posed.yaml");
  REQUIRE(s.pose.size() == 2);
  CHECK(s.pose.at("shoulder_abduction").node.as<double>() == 20);
  CHECK(s.pose.at("left_elbow_flexion").where.line == 4);
  // Written back and read again: the same pose.
  const Scene again = parse_scene(s.yaml(), "again.yaml");
  CHECK(again.pose.at("left_elbow_flexion").node.as<double>() == 45);
  // An A-pose scene's text has no pose (datasets keep the text they had).
  std::string unposed = kPosed;
  unposed.erase(unposed.find("  pose:"), unposed.find("garment:") - unposed.find("  pose:"));
  CHECK(parse_scene(unposed, "a.yaml").yaml().find("pose") == std::string::npos);

  const Simulation sim(plugins(), s);
  CHECK(sim.target_pose().angles.at("left_shoulder_abduction") == 20);
  CHECK(sim.target_pose().angles.at("right_shoulder_abduction") == 20);
  CHECK(sim.target_pose().angles.at("left_elbow_flexion") == 45);
  CHECK(sim.target_pose().angles.count("right_elbow_flexion") == 0);
}

TEST_CASE("a scene's bad pose is refused at its file and line", "[scene][pose]") {
  CHECK(scene_error("  pose: {sholder_abduction: 20}").find("posed.yaml:4: body `pose`: no joint angle 'sholder_abduction'; "
                                                           "did you mean") != std::string::npos);
  CHECK(scene_error("  pose: {elbow_flexion: 170}").find("posed.yaml:4: body `pose`: left_elbow_flexion = 170 is outside "
                                                        "its range of motion [0, 150]") != std::string::npos);
  CHECK(scene_error("  pose: {elbow_flexion: .nan}").find("left_elbow_flexion is NaN") != std::string::npos);
  CHECK(scene_error("  pose: {elbow_flexion: bent}").find("elbow_flexion = 'bent' is not a number of degrees") !=
        std::string::npos);
  CHECK(scene_error("  pose: {elbow_flexion: 30, left_elbow_flexion: 20}").find("left_elbow_flexion is set twice") !=
        std::string::npos);
  // Both names that set it, as --pose and a pose file say.
  CHECK(scene_error("  pose: {elbow_flexion: 30, left_elbow_flexion: 20}")
            .find("(by 'elbow_flexion' and by 'left_elbow_flexion')") != std::string::npos);
  CHECK(scene_error("  pose: [30]").find("posed.yaml:4: body `pose` must be a map of name: value") != std::string::npos);
}

TEST_CASE("a scene's morph_carry takes two distances, inner below outer", "[scene][pose]") {
  const auto error = [](const std::string& carry) {
    std::string text = kPosed;
    text.replace(text.find("settle_steps: 2}"), std::string("settle_steps: 2}").size(),
                 "settle_steps: 2, morph_carry: " + carry + "}");
    return message_of([&] { Simulation(plugins(), parse_scene(text, "posed.yaml")); });
  };
  CHECK(error("[0.02, 0.06]") == "(no exception)");
  for (const std::string bad : {"[0.06, 0.02]", "[0.02]", "[0.02, 0.04, 0.06]"}) {
    INFO(bad << ": " << error(bad));
    CHECK(error(bad).find("posed.yaml:7: solver: morph_carry must be two distances [inner, outer] in m with 0 <= inner "
                          "< outer <= 0.5") != std::string::npos);
  }
  // Each distance's bounds, and a number at all, are the parameter check's (scene_solver_specs).
  for (const std::string bad : {"[-0.01, 0.02]", "[0.02, 0.9]", "[0.02, .nan]"}) {
    INFO(bad << ": " << error(bad));
    CHECK(error(bad).find("posed.yaml:7: solver: parameter 'morph_carry'") != std::string::npos);
  }
}

TEST_CASE("a model without a skeleton refuses a scene's pose at its line", "[scene][pose]") {
  const auto body = skeletonless_body();
  const BodyModel& rigid = *body;
  Scene s = parse_scene(kPosed, "posed.yaml");
  s.body_model = "rigid";
  s.body_model_where = {};  // (set here, not in the file: no place to name)
  CHECK(message_of([&] { scene_pose(s, rigid); }) ==
        "posed.yaml:4: body `pose`: body model 'rigid' has no skeleton, so it cannot be posed (docs/poses.md says which "
        "models can)");
  s.pose.clear();
  CHECK(scene_pose(s, rigid).empty());
}

TEST_CASE("the body's path into a pose starts at the start body and ends on the posed target", "[scene][pose]") {
  for (const std::string path : {"together", "pose_first", "shape_first"}) {
    INFO(path);
    std::string text = kPosed;
    text.replace(text.find("settle_steps: 2}"), 16, "settle_steps: 2, pose_path: " + path + "}");
    const Simulation sim(plugins(), parse_scene(text, "posed.yaml"));
    const BodyModel& model = sim.body_model();
    const Eigen::VectorXd shape = sim.target_shape();
    const Eigen::MatrixX3d unposed = model.vertices(shape);
    const Eigen::MatrixX3d posed = model.posed(shape, sim.target_pose());
    SimulationOptions o;
    o.target_pose = &sim.target_pose();
    o.unposed_target = &unposed;
    const Eigen::MatrixX3d& start = sim.fit_body();
    const auto body_at = sim.body_path(o, start, posed);
    CHECK(body_at(0.0) == start);
    CHECK((body_at(1.0) - posed).cwiseAbs().maxCoeff() < 1e-12);
    // Halfway: both half done, or the first of the two done on the other's start.
    const Eigen::MatrixX3d half = body_at(0.5);
    Eigen::MatrixX3d expected;
    if (path == "together") expected = model.posed_vertices(0.5 * (start + unposed), sim.target_pose(), 0.5);
    if (path == "pose_first") expected = model.posed_vertices(start, sim.target_pose(), 1.0);
    if (path == "shape_first") expected = unposed;
    CHECK((half - expected).cwiseAbs().maxCoeff() < 1e-12);
    // A target that is not the unposed body in the pose is refused.
    const Eigen::MatrixX3d other = model.posed(shape, Pose{});
    CHECK(message_of([&] { sim.body_path(o, start, other); }).find("is not the unposed target in its pose") !=
          std::string::npos);
  }
  // Without a pose: the straight line of the A-pose scenes, as before.
  const Simulation sim(plugins(), parse_scene(kPosed, "posed.yaml"));
  const Eigen::MatrixX3d target = sim.body_vertices(sim.target_shape());
  const auto line = sim.body_path({}, sim.fit_body(), target);
  CHECK(line(0.25) == sim.fit_body() + 0.25 * (target - sim.fit_body()));
}

TEST_CASE("a posed drape settles off the body and off itself with the arms lowered and bent", "[scene][pose][solver]") {
  // The arms lowered to 20 degrees from the trunk press the sleeves towards
  // the shirt's sides; the elbows bend 45 degrees; friction and self-contact
  // as in the posed scenes.
  const Scene scene = parse_scene(
      posed_scene_text(30, 1.7, 0, "shoulder_abduction: 20, elbow_flexion: 45, spine_twist: 15", "resolution: 300"),
      "posed.yaml");
  const SceneSimulations simulations(plugins(), scene);
  const SceneBody body = scene_body(simulations, simulations.design().target_request(), "posed.yaml");
  REQUIRE(body.pose.angles.at("right_elbow_flexion") == 45);
  const SimulationResult r = drape_scene_body(body);
  INFO(r.unsettled);
  CHECK(r.converged);
  CHECK(r.penetration == 0);
  REQUIRE(r.crossings);
  CHECK(r.crossings->garment_edges_through_body == 0);
  CHECK(r.crossings->body_edges_through_garment == 0);
  // The drape is on the posed body, not the A-pose one.
  CHECK((r.body - body.vertices).cwiseAbs().maxCoeff() == 0);
  CHECK((r.body - body.unposed).cwiseAbs().maxCoeff() > 0.1);
  // Cloth through cloth: triangle-triangle tests of non-adjacent garment faces.
  CHECK(geometry::self_intersections(r.garment, simulations.design().garment().mesh.faces, 100).empty());
}
