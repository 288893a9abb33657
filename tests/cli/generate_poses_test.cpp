// drape generate --poses: each body in a drawn pose (or the scene's), the
// joint angles stored per sample, the shapes those of the same seed without
// poses, and a slim posed dataset's bodies rebuilt in their stored poses.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/assets/assets.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/h5.hpp>
#include <drape/scene/scene.hpp>
#include <drape/training/model.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

Pose pose_of(const DatasetReader& data, const Tensor& poses, int row) {
  Pose pose;
  for (std::size_t a = 0; a < data.layout().pose_angles.size(); ++a)
    pose.angles[data.layout().pose_angles[a]] = poses(row, 0, static_cast<int>(a));
  return pose;
}

}  // namespace

TEST_CASE("drape generate --poses draw stores each body's drawn pose and keeps the seed's shapes", "[cli][generate][pose]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string generate = "generate " + (dir / "tiny.yaml").string() + " --count 3 --bmi 15:40 --seed 6 --threads 1 ";
  std::string out;
  REQUIRE(test::run_drape(generate + "--poses draw --out " + (dir / "posed.h5").string(), out) == 0);
  INFO(out);
  REQUIRE(test::run_drape(generate + "--out " + (dir / "plain.h5").string(), out) == 0);
  REQUIRE(test::run_drape(generate + "--poses draw --pose-range shoulder_abduction=60:70,right_elbow_flexion=45 --out " +
                              (dir / "narrow.h5").string(), out) == 0);
  const DatasetReader posed(dir / "posed.h5"), plain(dir / "plain.h5"), narrow(dir / "narrow.h5");
  CHECK(plain.layout().pose_angles.empty());
  const auto model = test::parametric_body();
  std::vector<std::string> names;
  for (const PoseAngle& a : model->pose_angles()) names.push_back(a.name);
  REQUIRE(posed.layout().pose_angles == names);
  CHECK(posed.layout().attributes.at("generator").find("; poses drawn") != std::string::npos);
  CHECK(narrow.layout().attributes.at("generator").find("left_shoulder_abduction 60:70") != std::string::npos);
  const auto idx = posed.indices();
  REQUIRE(idx.size() == 3);
  const Tensor poses = posed.poses(idx), narrow_poses = narrow.poses(idx);
  const Tensor shapes = posed.body_params(idx), plain_shapes = plain.body_params(idx);
  const Tensor bodies = posed.body_vertices(idx), plain_bodies = plain.body_vertices(idx);
  for (int i = 0; i < 3; ++i) {
    CHECK(shapes.mat(i) == plain_shapes.mat(i));  // the pose's stream is its own
    const Pose pose = pose_of(posed, poses, i);
    for (const PoseAngle& a : model->pose_angles()) {
      CHECK(pose.angles.at(a.name) >= a.sample_lo);
      CHECK(pose.angles.at(a.name) <= a.sample_hi);
    }
    // The stored body is the body of the stored shape in the stored angles.
    const Eigen::VectorXd shape = shapes.mat(i).row(0).transpose().cast<double>();
    const Eigen::MatrixX3d expected = model->posed_vertices(model->vertices(shape), pose, 1.0);
    CHECK((bodies.mat(i).cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-5);
    CHECK((bodies.mat(i) - plain_bodies.mat(i)).cwiseAbs().maxCoeff() > 0.01f);  // posed, not the A-pose body
    const Pose narrowed = pose_of(narrow, narrow_poses, i);
    for (const char* side : {"left_", "right_"}) {
      CHECK(narrowed.angles.at(std::string(side) + "shoulder_abduction") >= 60);
      CHECK(narrowed.angles.at(std::string(side) + "shoulder_abduction") <= 70);
    }
    CHECK(narrowed.angles.at("right_elbow_flexion") == 45);
  }
  // What the unposing graphs read: the rest body and the joints' transforms
  // pose it by the body's own weights into the stored body; the angles in radians.
  const DatasetReader::Posing posing = posed.posing(idx);
  REQUIRE(posing.transforms.rows() == static_cast<int>(model->joints().size()));
  for (int i = 0; i < 3; ++i) {
    const std::vector<skinning::Rigid> transforms = transforms_of_rows(posing.transforms, i);
    const Eigen::MatrixX3d unposed = posing.unposed.mat(i).cast<double>();
    const Eigen::MatrixX3d skinned = skinning::blend(unposed, model->skinning_weights(), transforms);
    CHECK((skinned - bodies.mat(i).cast<double>()).cwiseAbs().maxCoeff() < 1e-4);
    CHECK(posing.angles(i, 0, 2) == Approx(poses(i, 0, 2) * M_PI / 180).epsilon(1e-5));  // spine_twist
  }
  // An A-pose dataset's samples are at rest: identity transforms, the body itself.
  const DatasetReader::Posing at_rest = plain.posing({0});
  CHECK(at_rest.transforms(0, 3, 0) == 1.0f);
  CHECK(at_rest.transforms(0, 3, 9) == 0.0f);
  CHECK((at_rest.unposed.mat(0) - plain_bodies.mat(0)).cwiseAbs().maxCoeff() < 1e-5f);
  REQUIRE(test::run_drape("dataset info " + (dir / "posed.h5").string(), out) == 0);
  CHECK(out.find("poses     22 joint angles per body, degrees") != std::string::npos);
  REQUIRE(test::run_drape("dataset info " + (dir / "plain.h5").string(), out) == 0);
  CHECK(out.find("poses     none: the bodies are in the body model's A-pose") != std::string::npos);
  // Slim, the bodies come back posed in their stored angles.
  REQUIRE(test::run_drape("dataset slim " + (dir / "posed.h5").string() + " --out " + (dir / "slim.h5").string(), out) == 0);
  const DatasetReader slim(dir / "slim.h5");
  CHECK(!slim.layout().body_vertices_stored);
  const Tensor rebuilt = slim.body_vertices(idx);
  CHECK(slim.poses(idx).mat(1) == poses.mat(1));
  for (int i = 0; i < 3; ++i) CHECK((rebuilt.mat(i) - bodies.mat(i)).cwiseAbs().maxCoeff() < 1e-5f);
  CHECK_NOTHROW(DatasetReader(dir / "slim.h5").posing(idx));  // each posed body checked against its witness, and passing
  // A stored pose the generator did not simulate (the first angle of sample 1
  // moved 10 degrees): posing() poses that body to check it against the
  // witness of the simulated one, and refuses it by file and sample.
  fs::copy_file(dir / "slim.h5", dir / "moved.h5");
  {
    h5::File file = h5::File::open(dir / "moved.h5", h5::Access::ReadWrite);
    std::vector<float> angles = file.read<float>("/bodies/pose");
    angles[names.size()] += 10.0f;
    file.write_rows("/bodies/pose", 0, 3, angles.data());
  }
  CHECK_THROWS_WITH(DatasetReader(dir / "moved.h5").posing({1}),
                    Catch::Contains("moved.h5: sample 1's body") && Catch::Contains("not the body its drape was simulated on"));
  REQUIRE(test::run_drape("dataset expand " + (dir / "slim.h5").string() + " --out " + (dir / "whole.h5").string(), out) == 0);
  const DatasetReader whole(dir / "whole.h5");
  CHECK(whole.layout().pose_angles == names);
  CHECK((whole.body_vertices(idx).mat(2) - bodies.mat(2)).cwiseAbs().maxCoeff() < 1e-5f);
  // An A-pose dataset of the same scene, up to its solver (the posed scenes
  // carry the cloth with a rising arm), reads as one with the posed one: the
  // A-pose bodies as they are, at their rest angles, and posing() at rest.
  std::string other_solver = test::tiny_simulation_scene();
  other_solver.replace(other_solver.find("settle_steps: 3"), 15, "settle_steps: 4");
  std::ofstream(dir / "solver.yaml") << other_solver;
  REQUIRE(test::run_drape("generate " + (dir / "solver.yaml").string() + " --count 2 --bmi 15:40 --seed 7 --threads 1 --out " +
                              (dir / "a-pose.h5").string(), out) == 0);
  const DatasetReader a_pose(dir / "a-pose.h5");
  const Tensor a_bodies = a_pose.body_vertices({0, 1});
  // One pattern names both files ({a,b} alternatives, in their order).
  const DatasetReader mixed((dir / "{slim,a-pose}.h5").string());
  CHECK(mixed.mixed_poses());
  REQUIRE(mixed.size() == 5);
  CHECK(mixed.layout().pose_angles == names);
  CHECK(mixed.layout().scene == slim.layout().scene);
  const Tensor mixed_bodies = mixed.body_vertices({0, 1, 2, 3, 4}), mixed_poses = mixed.poses({0, 3, 4});
  for (int i = 0; i < 3; ++i) CHECK((mixed_bodies.mat(i) - bodies.mat(i)).cwiseAbs().maxCoeff() < 1e-5f);
  CHECK(mixed_poses.mat(0) == poses.mat(0));
  for (int i = 0; i < 2; ++i) {
    CHECK(mixed_bodies.mat(3 + i) == a_bodies.mat(i));
    // Its angles are the rest pose: they pose the A-pose body into itself,
    // and they are the body model's A-pose (arms down and out), not zeros.
    const Pose rest = pose_of(mixed, mixed_poses, 1 + i);
    const Eigen::MatrixX3d a = a_bodies.mat(i).cast<double>();
    CHECK((model->posed_vertices(a, rest, 1.0) - a).cwiseAbs().maxCoeff() < 1e-5);
    CHECK(rest.angles.at("left_shoulder_abduction") > 20);
  }
  REQUIRE(test::run_drape("dataset info '" + (dir / "{slim,a-pose}.h5").string() + "'", out) == 0);
  CHECK(out.find("2 files read as one") != std::string::npos);
  CHECK(out.find("22 joint angles per body, degrees (/bodies/pose; docs/poses.md); the A-pose files' bodies at their "
                 "rest angles") != std::string::npos);
  const DatasetReader::Posing mixed_rest = mixed.posing({4});
  CHECK(mixed_rest.transforms(0, 3, 0) == 1.0f);
  CHECK(mixed_rest.transforms(0, 3, 9) == 0.0f);
  CHECK((mixed_rest.unposed.mat(0) - a_bodies.mat(1)).cwiseAbs().maxCoeff() < 1e-5f);
  // A scene that drapes something else does not mix (here the contact's margin).
  std::string other_scene = test::tiny_simulation_scene();
  other_scene.replace(other_scene.find("margin: 0.004"), 13, "margin: 0.005");
  std::ofstream(dir / "other.yaml") << other_scene;
  REQUIRE(test::run_drape("generate " + (dir / "other.yaml").string() + " --count 1 --bmi 15:40 --seed 7 --threads 1 --out " +
                              (dir / "other.h5").string(), out) == 0);
  CHECK_THROWS_WITH(DatasetReader((dir / "{posed,other}.h5").string()),
                    Catch::Contains("in the file, none (A-pose bodies) now (an A-pose file is read with posed ones when only their "
                                                    "solvers differ; here the scene YAML differs: line ") &&
                        Catch::Contains("{margin: 0.004, stiffness: 1.0e8}' in the file, '  collision: {margin: 0.005"));
}

TEST_CASE("drape generate in a posed scene stores the scene's pose for every body", "[cli][generate][pose]") {
  test::TempDir dir;
  {
    std::ofstream scene(dir / "posed.yaml");
    std::string text = test::tiny_simulation_scene();
    text.replace(text.find("body: {model: parametric}"), 25, "body: {model: parametric, pose: {left_elbow_flexion: 40}}");
    scene << text;
  }
  std::string out;
  REQUIRE(test::run_drape("generate " + (dir / "posed.yaml").string() + " --count 2 --seed 1 --threads 1 --out " +
                              (dir / "d.h5").string(), out) == 0);
  INFO(out);
  const DatasetReader data(dir / "d.h5");
  const auto model = test::parametric_body();
  const Tensor poses = data.poses(data.indices()), shapes = data.body_params(data.indices());
  for (int i = 0; i < 2; ++i) {
    const Pose pose = pose_of(data, poses, i);
    CHECK(pose.angles.at("left_elbow_flexion") == 40);
    // Angles the scene leaves alone are stored at the body's rest angles.
    const Eigen::VectorXd shape = shapes.mat(i).row(0).transpose().cast<double>();
    const Pose rest = model->rest_pose(shape);
    CHECK(pose.angles.at("right_elbow_flexion") == Approx(rest.angles.at("right_elbow_flexion")).margin(1e-5));
    CHECK(pose.angles.at("left_shoulder_abduction") == Approx(rest.angles.at("left_shoulder_abduction")).margin(1e-5));
  }
}

TEST_CASE("drape generate refuses poses it cannot draw before writing anything", "[cli][generate][pose]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string generate = "generate " + (dir / "tiny.yaml").string() + " --count 1 --out " + (dir / "d.h5").string();
  std::string out;
  CHECK(test::run_drape(generate + " --pose-range shoulder_abduction=60:90", out) == 2);
  CHECK(out.find("draw poses too (--poses draw)") != std::string::npos);
  CHECK(test::run_drape(generate + " --poses draw --pose-range shoulder_abdution=60:90", out) == 2);
  CHECK(out.find("pose range: no joint angle 'shoulder_abdution'; did you mean 'shoulder_abduction'") != std::string::npos);
  CHECK(test::run_drape(generate + " --poses draw --pose-range spine_twist=30:60", out) == 2);
  CHECK(out.find("spine_twist = 60 is outside its range of motion [-45, 45] degrees") != std::string::npos);
  CHECK(test::run_drape(generate + " --poses draw --pose-range spine_twist=30:10", out) == 2);
  CHECK(out.find("spine_twist range 30:10: expected lo <= hi") != std::string::npos);
  CHECK(test::run_drape(generate + " --poses sometimes", out) == 2);
  CHECK(out.find("--poses sometimes: expected scene or draw") != std::string::npos);
  const std::string scene = (test::source_dir() / "graphs" / "scenes" / "tshirt_coarse_posed.yaml").string();
  CHECK(test::run_drape("generate " + scene + " --poses draw --count 1 --out " + (dir / "d.h5").string(), out) == 2);
  INFO(out);
  CHECK(out.find("tshirt_coarse_posed.yaml:9: body `pose`: this scene drapes one pose and poses are to be drawn") !=
        std::string::npos);
  CHECK(!fs::exists(dir / "d.h5"));
  CHECK(!fs::exists(dir / "d.h5.partial"));
}

TEST_CASE("drape dataset unpose brings posed drapes back to the rest pose", "[cli][dataset][pose]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string generate = "generate " + (dir / "tiny.yaml").string() + " --count 4 --bmi 20:35 --seed 3 --threads 1 ";
  std::string out;
  REQUIRE(test::run_drape(generate + "--poses draw --out " + (dir / "posed.h5").string(), out) == 0);
  REQUIRE(test::run_drape(generate + "--out " + (dir / "plain.h5").string(), out) == 0);
  REQUIRE(test::run_drape("dataset unpose " + (dir / "posed.h5").string() + " --out " + (dir / "rest.h5").string(), out) == 0);
  INFO(out);
  CHECK(test::run_drape("dataset unpose " + (dir / "plain.h5").string() + " --out " + (dir / "x.h5").string(), out) == 2);
  CHECK(out.find("holds A-pose bodies (no /bodies/pose): there is nothing to unpose") != std::string::npos);
  const DatasetReader posed(dir / "posed.h5"), plain(dir / "plain.h5"), rest(dir / "rest.h5");
  CHECK(rest.layout().pose_angles.empty());
  CHECK(rest.layout().has_stat("pose_left_shoulder_abduction"));
  const auto idx = posed.indices();
  const Tensor at_rest = rest.garment_vertices(idx), in_pose = posed.garment_vertices(idx);
  const Tensor rest_bodies = rest.body_vertices(idx), plain_bodies = plain.body_vertices(idx);
  // The skin node's weights: posing the drapes at rest again gives the simulated ones back.
  const Scene scene = parse_scene(posed.layout().scene, "posed.h5");
  const Eigen::MatrixXd weights = build_assets(test::plugins(), assets_spec_for(scene, 1, 1), "")->garment_skinning.cast<double>();
  const DatasetReader::Posing posing = posed.posing(idx);
  for (int i = 0; i < 4; ++i) {
    // The bodies are the A-pose bodies of the same shapes; the angles kept as statistics.
    CHECK((rest_bodies.mat(i) - plain_bodies.mat(i)).cwiseAbs().maxCoeff() < 1e-5f);
    CHECK(rest.stat("pose_spine_twist", {idx[static_cast<std::size_t>(i)]})[0] ==
          Approx(posed.poses({idx[static_cast<std::size_t>(i)]})(0, 0, 2)));
    const std::vector<skinning::Rigid> transforms = transforms_of_rows(posing.transforms, i);
    const Eigen::MatrixX3d again = pose_garment(at_rest.mat(i).cast<double>(), weights, transforms);
    CHECK((again - in_pose.mat(i).cast<double>()).cwiseAbs().maxCoeff() < 1e-5);
    CHECK((at_rest.mat(i) - in_pose.mat(i)).cwiseAbs().maxCoeff() > 0.01f);  // it did move
  }
}
