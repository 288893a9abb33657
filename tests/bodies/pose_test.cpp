// Posing the parametric body: the zero pose is the unposed body bit for bit,
// joints follow the shape, skinning weights are a smooth partition of unity,
// an elbow flexion bends the forearm by as much (measured on the mesh), posed
// bodies stay watertight and free of self-intersection, and bad poses are
// refused in one line naming the angle or the joints.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/bodies/body_space.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/volume.hpp>
#include <test_support.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

namespace {

using namespace drape;

const BodyModel& posed_model() {
  static const std::unique_ptr<BodyModel> model = test::parametric_body();
  return *model;
}

int joint_index(const std::string& name) {
  const auto joints = posed_model().joints();
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  FAIL("no joint " << name);
  return -1;
}

Eigen::VectorXd shape_of(double bmi, double height, double sex) { return posed_model().solve({bmi, height, sex, {}}); }

Pose pose_of(const std::string& text) { return parse_pose(text, posed_model().pose_angles(), "test"); }

// A ring of the unposed body around the segment a-b at fraction t of its
// length: the vertices within 1 cm of that cross-section's plane and 12 cm
// of the axis, kept to those connected (within the slab) to the one nearest
// the axis, so that the trunk beside an arm is left out. Chosen from the rest
// geometry alone, not from the skinning.
std::vector<int> ring_at(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, double t) {
  const Eigen::Vector3d d = (b - a).normalized(), c = a + t * (b - a);
  std::vector<char> in(static_cast<std::size_t>(v.rows()), 0);
  int nearest = -1;
  double best = 1e300;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Vector3d p = v.row(i).transpose() - c;
    const double along = p.dot(d), across = (p - along * d).norm();
    if (std::abs(along) > 0.01 || across > 0.12) continue;
    in[static_cast<std::size_t>(i)] = 1;
    if (across < best) best = across, nearest = static_cast<int>(i);
  }
  const auto nb = geometry::vertex_neighbours(f, static_cast<int>(v.rows()));
  std::vector<int> out{nearest}, stack{nearest};
  std::vector<char> seen(in.size(), 0);
  seen[static_cast<std::size_t>(nearest)] = 1;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    for (int u : nb[static_cast<std::size_t>(i)])
      if (in[static_cast<std::size_t>(u)] && !seen[static_cast<std::size_t>(u)]) {
        seen[static_cast<std::size_t>(u)] = 1;
        out.push_back(u);
        stack.push_back(u);
      }
  }
  return out;
}

Eigen::Vector3d centroid(const Eigen::MatrixX3d& v, const std::vector<int>& ids) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i : ids) c += v.row(i).transpose();
  return c / static_cast<double>(ids.size());
}

double angle_between_degrees(Eigen::Vector3d a, Eigen::Vector3d b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("the zero pose gives the unposed body bit for bit", "[bodies][pose]") {
  REQUIRE(posed_model().poseable());
  for (const auto& shape : {posed_model().mean_shape(), shape_of(10, 1.5, 0), shape_of(65, 2.0, 1), shape_of(30, 1.75, 0.5)}) {
    const Eigen::MatrixX3d rest = posed_model().vertices(shape);
    CHECK((posed_model().posed(shape, Pose{}).array() == rest.array()).all());
    // Through the skinning itself: every angle set to its rest value.
    const Pose at_rest = posed_model().rest_pose(shape);
    REQUIRE(at_rest.angles.size() == posed_model().pose_angles().size());
    CHECK((posed_model().posed(shape, at_rest).array() == rest.array()).all());
    // A pose that moves only the elbows leaves the legs where they were, exactly.
    const Eigen::MatrixX3d bent = posed_model().posed(shape, pose_of("elbow_flexion=30"));
    const int shin = joint_index("left_shin");
    const Eigen::MatrixXd w = posed_model().skinning_weights();
    int exact = 0;
    for (Eigen::Index v = 0; v < rest.rows(); ++v)
      if (w(v, shin) > 0.99) exact += (bent.row(v).array() == rest.row(v).array()).all();
    CHECK(exact > 50);
  }
}

TEST_CASE("joints follow the body's height and build", "[bodies][pose]") {
  const int knee = joint_index("left_shin"), hip_l = joint_index("left_thigh"), hip_r = joint_index("right_thigh");
  const int elbow = joint_index("left_forearm"), shoulder = joint_index("left_upper_arm");
  const Eigen::MatrixX3d short_j = posed_model().joint_positions(shape_of(25, 1.6, 1));
  const Eigen::MatrixX3d tall_j = posed_model().joint_positions(shape_of(25, 1.9, 1));
  CHECK(tall_j(knee, 1) > short_j(knee, 1) + 0.05);
  // About at knee height: 0.27-0.30 of the height (anthropometric tables).
  CHECK(short_j(knee, 1) / 1.6 == Approx(0.285).margin(0.03));
  const Eigen::MatrixX3d lean_j = posed_model().joint_positions(shape_of(20, 1.75, 0));
  const Eigen::MatrixX3d heavy_j = posed_model().joint_positions(shape_of(50, 1.75, 0));
  CHECK(heavy_j(hip_l, 0) - heavy_j(hip_r, 0) > lean_j(hip_l, 0) - lean_j(hip_r, 0) + 0.02);
  // Joints sit in the limbs: left ones at +x, the elbow below the shoulder, the
  // hips below the spine.
  for (const auto* j : {&short_j, &tall_j, &lean_j, &heavy_j}) {
    CHECK((*j)(hip_l, 0) > 0);
    CHECK((*j)(hip_r, 0) < 0);
    CHECK((*j)(elbow, 1) < (*j)(shoulder, 1));
    CHECK((*j)(hip_l, 1) < (*j)(joint_index("spine_lower"), 1));
  }
}

TEST_CASE("skinning weights sum to 1 and change smoothly between neighbours", "[bodies][pose]") {
  const Eigen::MatrixXd w = posed_model().skinning_weights();
  REQUIRE(w.rows() == posed_model().num_vertices());
  REQUIRE(w.cols() == static_cast<Eigen::Index>(posed_model().joints().size()));
  CHECK(w.minCoeff() >= 0);
  CHECK((w.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  double worst = 0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  const Eigen::MatrixX3d mean = posed_model().vertices(posed_model().mean_shape());
  const auto nb = geometry::vertex_neighbours(posed_model().faces(), posed_model().num_vertices());
  for (Eigen::Index v = 0; v < w.rows(); ++v)
    for (int u : nb[static_cast<std::size_t>(v)])
      if ((w.row(v) - w.row(u)).cwiseAbs().maxCoeff() > worst) {
        worst = (w.row(v) - w.row(u)).cwiseAbs().maxCoeff();
        where = mean.row(v).transpose();
      }
  INFO("largest weight step along an edge " << worst << " at " << where.transpose());
  CHECK(worst < 0.3);
  // Every bone owns some skin outright.
  for (Eigen::Index b = 0; b < w.cols(); ++b) CHECK(w.col(b).maxCoeff() > 0.95);
}

TEST_CASE("a 90 degree elbow flexion bends the forearm by 90 degrees on the mesh", "[bodies][pose]") {
  for (const auto& shape : {posed_model().mean_shape(), shape_of(45, 1.6, 0)}) {
    const Eigen::MatrixX3d rest = posed_model().vertices(shape);
    const Eigen::MatrixX3d j = posed_model().joint_positions(shape);
    const Eigen::Vector3d s = j.row(joint_index("left_upper_arm")).transpose();
    const Eigen::Vector3d e = j.row(joint_index("left_forearm")).transpose();
    const Eigen::Vector3d w = e + (e - s).normalized() * 0.24;  // towards the wrist
    // Two rings on each bone, away from the blends at shoulder and elbow.
    const auto u0 = ring_at(rest, posed_model().faces(), s, e, 0.4), u1 = ring_at(rest, posed_model().faces(), s, e, 0.7);
    const auto f0 = ring_at(rest, posed_model().faces(), e, w, 0.4), f1 = ring_at(rest, posed_model().faces(), e, w, 0.8);
    for (const auto* r : {&u0, &u1, &f0, &f1}) REQUIRE(r->size() >= 8);
    auto axis = [](const Eigen::MatrixX3d& v, const std::vector<int>& a, const std::vector<int>& b) {
      return Eigen::Vector3d(centroid(v, b) - centroid(v, a));
    };
    for (double flexion : {45.0, 90.0}) {
      const Eigen::MatrixX3d bent = posed_model().posed(shape, pose_of("left_elbow_flexion=" + std::to_string(flexion)));
      // The upper arm stays; the forearm turns by the flexion.
      const double upper_turn = angle_between_degrees(axis(rest, u0, u1), axis(bent, u0, u1));
      const double fore_turn = angle_between_degrees(axis(rest, f0, f1), axis(bent, f0, f1));
      INFO("flexion " << flexion << ": upper arm turned " << upper_turn << ", forearm " << fore_turn);
      CHECK(upper_turn < 1);
      CHECK(fore_turn == Approx(flexion).margin(3));
      // Forwards: the hand goes to +z.
      CHECK(centroid(bent, f1).z() > centroid(rest, f1).z() + 0.05);
    }
  }
}

TEST_CASE("part of a pose turns each joint by that part of its way from the body's own rest", "[bodies][pose]") {
  const Eigen::VectorXd thin = shape_of(18, 1.6, 0), heavy = shape_of(45, 1.85, 1);
  const Pose pose = pose_of("left_elbow_flexion=80,left_shoulder_abduction=90");
  const Eigen::MatrixX3d rest = posed_model().vertices(heavy);
  // The ends: nothing at 0 (also on a mesh between two shapes, as a morph
  // passes through), posed() at 1, bit for bit.
  const Eigen::MatrixX3d between = 0.5 * (posed_model().vertices(thin) + rest);
  CHECK(posed_model().posed_vertices(between, pose, 0.0) == between);
  CHECK(posed_model().posed_vertices(rest, pose, 1.0) == posed_model().posed(heavy, pose));
  // Halfway: the forearm turns half the flexion about the elbow and the upper
  // arm half its way from the A-pose's abduction (measured per body) to 90.
  const Eigen::MatrixX3d j = posed_model().joint_positions(heavy);
  const Eigen::Vector3d s = j.row(joint_index("left_upper_arm")).transpose();
  const Eigen::Vector3d e = j.row(joint_index("left_forearm")).transpose();
  const Eigen::Vector3d w = e + (e - s).normalized() * 0.24;
  const auto u0 = ring_at(rest, posed_model().faces(), s, e, 0.4), u1 = ring_at(rest, posed_model().faces(), s, e, 0.7);
  const auto f0 = ring_at(rest, posed_model().faces(), e, w, 0.4), f1 = ring_at(rest, posed_model().faces(), e, w, 0.8);
  for (const auto* r : {&u0, &u1, &f0, &f1}) REQUIRE(r->size() >= 8);
  auto axis = [](const Eigen::MatrixX3d& v, const std::vector<int>& a, const std::vector<int>& b) {
    return Eigen::Vector3d(centroid(v, b) - centroid(v, a));
  };
  const double abduction_at_rest = posed_model().rest_pose(heavy).angles.at("left_shoulder_abduction");
  const Eigen::MatrixX3d half = posed_model().posed_vertices(rest, pose, 0.5);
  const double upper_turn = angle_between_degrees(axis(rest, u0, u1), axis(half, u0, u1));
  // The forearm's turn against the same body with only the shoulder turned halfway: the flexion alone.
  Pose shoulder_only;
  shoulder_only.angles["left_shoulder_abduction"] = abduction_at_rest + 0.5 * (90 - abduction_at_rest);
  const Eigen::MatrixX3d arm_only = posed_model().posed(heavy, shoulder_only);
  const double bend = angle_between_degrees(axis(arm_only, f0, f1), axis(half, f0, f1));
  INFO("rest abduction " << abduction_at_rest << "; upper arm turned " << upper_turn << ", elbow bent " << bend);
  CHECK(upper_turn == Approx(0.5 * (90 - abduction_at_rest)).margin(2));
  CHECK(bend == Approx(40).margin(3));
  CHECK_THROWS_WITH(posed_model().posed_vertices(rest.topRows(10), pose, 0.5), Catch::Contains("10 vertices"));
}

TEST_CASE("posed bodies over shape and pose draws are watertight and uncrossed", "[bodies][pose]") {
  // A few draws here; scripts/pose_space_check.sh runs 200 (docs/poses.md).
  BodySpace space;
  Rng shapes(7), poses(Rng::derive(7, "poses"));
  int redraws = 0;
  constexpr int kBodies = 6;
  for (int i = 0; i < kBodies; ++i) {
    BodyRequest request = draw_body(space, posed_model(), shapes);
    const Eigen::VectorXd shape = solve_in_space(posed_model(), request);
    for (int tries = 0;; ++tries) {
      REQUIRE(tries < 50);
      const Pose pose = draw_pose(posed_model().pose_angles(), poses);
      const Eigen::MatrixX3d posed = posed_model().posed(shape, pose);
      if (!describe_pose_crossings(posed_model(), shape, pose, posed).empty()) {
        ++redraws;
        continue;
      }
      INFO("body " << i << " pose " << format_pose(pose));
      const auto topo = geometry::check_topology(posed_model().faces(), posed_model().num_vertices());
      CHECK(topo.closed_manifold());
      // Volume is kept within 8 % (skinning loses some at bent joints) and no
      // edge passes through a face (a test other than the face pairs').
      const double v0 = geometry::mesh_volume(posed_model().vertices(shape), posed_model().faces());
      CHECK(geometry::mesh_volume(posed, posed_model().faces()) == Approx(v0).epsilon(0.08));
      CHECK(geometry::self_edge_crossings(posed, posed_model().faces(), 1).empty());
      break;
    }
  }
  INFO("redraws " << redraws);
  CHECK(redraws < 3 * kBodies);
}

TEST_CASE("elbows and knees bent past plain LBS's reach stay uncrossed (the hinge corrective)", "[bodies][pose]") {
  // Plain LBS folds the forearm into the upper arm from 73-101 degrees and the
  // calf into the thigh from 68-105 (docs/poses.md); the corrective presses
  // each crease flat against the plane between the two bones. A BMI 10 man
  // and a BMI 65 woman, the ends of the body space.
  for (const auto& shape : {shape_of(10, 1.75, 1), shape_of(65, 1.6, 0)}) {
    for (const char* text : {"knee_flexion=100", "knee_flexion=115", "elbow_flexion=130", "elbow_flexion=150"}) {
      const Pose pose = pose_of(text);
      const Eigen::MatrixX3d posed = posed_model().posed(shape, pose);
      INFO(text);
      CHECK(describe_pose_crossings(posed_model(), shape, pose, posed).empty());
      CHECK(geometry::self_edge_crossings(posed, posed_model().faces(), 1).empty());
    }
  }
  // Inside the sampled ranges (knees to 60, elbows to 70) it adds nothing:
  // the 60-degree knee's shin is the rigid turn of the rest shin about the
  // knee wherever the shin's weight is whole.
  const Eigen::VectorXd shape = shape_of(30, 1.75, 1);
  const Eigen::MatrixX3d rest = posed_model().vertices(shape), j = posed_model().joint_positions(shape);
  const Eigen::MatrixX3d bent = posed_model().posed(shape, pose_of("left_knee_flexion=60"));
  const Eigen::Vector3d knee = j.row(joint_index("left_shin")).transpose();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(60 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::MatrixXd weights = posed_model().skinning_weights();
  int whole = 0;
  for (Eigen::Index i = 0; i < rest.rows(); ++i) {
    if (weights(i, joint_index("left_shin")) < 1 - 1e-12) continue;
    ++whole;
    const Eigen::Vector3d expected = knee + turn * (rest.row(i).transpose() - knee);
    CHECK((bent.row(i).transpose() - expected).norm() < 1e-9);
  }
  CHECK(whole > 100);
}

TEST_CASE("a pose that makes the body cross itself is refused naming the joints", "[bodies][pose]") {
  const Eigen::VectorXd shape = shape_of(35, 1.75, 1);
  const std::string arms = test::message_of([&] { pose_body(posed_model(), "parametric", shape, pose_of("left_shoulder_abduction=0")); });
  INFO(arms);
  CHECK(arms.find("pass through itself") != std::string::npos);
  CHECK(arms.find("left_upper_arm") != std::string::npos);
  CHECK(arms.find("left_shoulder_abduction=0") != std::string::npos);
  const std::string legs = test::message_of([&] { pose_body(posed_model(), "parametric", shape, pose_of("hip_abduction=-25")); });
  INFO(legs);
  CHECK(legs.find("right_thigh into left_thigh") != std::string::npos);
  // A pose well inside the space is not refused.
  CHECK_NOTHROW(pose_body(posed_model(), "parametric", shape, pose_of("shoulder_abduction=70,elbow_flexion=40,spine_twist=20")));
}

TEST_CASE("bad joint angles are refused in one line", "[bodies][pose]") {
  const auto angles = posed_model().pose_angles();
  auto message = [&](const std::string& text) { return test::message_of([&] { parse_pose(text, angles, "--pose"); }); };
  CHECK(message("sholder_abduction=40") ==
        "--pose: no joint angle 'sholder_abduction'; did you mean 'shoulder_abduction', 'left_shoulder_abduction', "
        "'right_shoulder_abduction'?");
  CHECK(message("left_elbow_flexion=nan").find("left_elbow_flexion is NaN; expected a number in [0, 150] degrees") != std::string::npos);
  CHECK(message("elbow_flexion=170").find("left_elbow_flexion = 170 is outside its range of motion [0, 150] degrees") !=
        std::string::npos);
  // Just past a bound, printed as given (it read "= 150 is outside ... [0, 150]").
  CHECK(message("elbow_flexion=150.0000001").find("= 150.0000001 is outside its range of motion [0, 150]") != std::string::npos);
  CHECK(message("elbow_flexion=abc") == "--pose: elbow_flexion = 'abc' is not a number of degrees");
  // strtod reads C's hexadecimal numbers: 0x10 was taken for 16 degrees.
  CHECK(message("elbow_flexion=0x10") == "--pose: elbow_flexion = '0x10' is not a number of degrees");
  // Both names that set it (it said "by 'left_elbow_flexion' and before").
  CHECK(message("elbow_flexion=10,left_elbow_flexion=20") ==
        "--pose: left_elbow_flexion is set twice (by 'elbow_flexion' and by 'left_elbow_flexion')");
  // An overflow is said as written (it said "= inf is outside ..."), with
  // the range (docs/poses.md's table: 0 ... 180 and 0 ... 135; it named none).
  CHECK(message("shoulder_abduction=1e400") ==
        "--pose: shoulder_abduction = 1e400 is beyond any angle; expected a number in [0, 180] degrees");
  CHECK(message("right_knee_flexion=-1e309") ==
        "--pose: right_knee_flexion = -1e309 is beyond any angle; expected a number in [0, 135] degrees");
  CHECK(message("sholder_abduction=1e400").find("did you mean") != std::string::npos);
  CHECK(message("knee").find("expected name=degrees") != std::string::npos);
  for (const char* text : {"sholder_abduction=40", "elbow_flexion=nan", "elbow_flexion=170"})
    CHECK(message(text).find('\n') == std::string::npos);
  // Unsided names set both sides; sided ones one.
  const Pose both = parse_pose("shoulder_abduction=60, right_knee_flexion=10", angles, "--pose");
  CHECK(both.angles.size() == 3);
  CHECK(both.angles.at("left_shoulder_abduction") == 60);
  CHECK(both.angles.at("right_shoulder_abduction") == 60);
  CHECK(parse_pose(format_pose(both), angles, "again").angles == both.angles);
}

TEST_CASE("a pose file is read and checked like --pose", "[bodies][pose]") {
  test::TempDir dir;
  {
    std::ofstream(dir / "pose.yaml") << "shoulder_abduction: 80\nleft_elbow_flexion: 45\n";
    std::ofstream(dir / "bad.yaml") << "shoulder_abduction: 80\nknee_flexion: 200\n";
    std::ofstream(dir / "list.yaml") << "[1, 2, 3]\n";
    std::ofstream(dir / "twice.yaml") << "left_elbow_flexion: 30\nleft_elbow_flexion: 60\n";
    std::ofstream(dir / "both.yaml") << "elbow_flexion: 30\nleft_elbow_flexion: 60\n";
    std::ofstream(dir / "nested.yaml") << "# my pose\npose:\n  shoulder_abduction: 60\n";
  }
  const Pose p = read_pose_file((dir / "pose.yaml").string(), posed_model().pose_angles());
  CHECK(p.angles.size() == 3);
  CHECK(test::message_of([&] { read_pose_file((dir / "bad.yaml").string(), posed_model().pose_angles()); })
            .find("bad.yaml:2: left_knee_flexion = 200 is outside its range of motion [0, 135]") != std::string::npos);
  CHECK(test::message_of([&] { read_pose_file((dir / "list.yaml").string(), posed_model().pose_angles()); })
            .find("expected a map of joint angle names to degrees") != std::string::npos);
  // An angle written twice is refused at its second line, not kept once.
  CHECK(test::message_of([&] { read_pose_file((dir / "twice.yaml").string(), posed_model().pose_angles()); })
            .find("twice.yaml:2: 'left_elbow_flexion' is defined twice") != std::string::npos);
  CHECK_THAT(test::message_of([&] { read_pose_file((dir / "both.yaml").string(), posed_model().pose_angles()); }),
             Catch::Contains("both.yaml:2: left_elbow_flexion is set twice (by 'elbow_flexion' and by 'left_elbow_flexion')"));
  // A map nested under a key that is no angle: the key named, at its own line (it said "k.yaml:3: pose wants one number").
  CHECK_THAT(test::message_of([&] { read_pose_file((dir / "nested.yaml").string(), posed_model().pose_angles()); }),
             Catch::Contains("nested.yaml:2: no joint angle 'pose'"));
}

TEST_CASE("a body model without a skeleton refuses a pose naming itself", "[bodies][pose]") {
  const auto body = test::skeletonless_body();
  const BodyModel& rigid = *body;
  Pose p;
  p.angles["left_elbow_flexion"] = 10;
  CHECK(test::message_of([&] { pose_body(rigid, "rigid", {}, p); }) ==
        "body rigid has no skeleton, so it cannot be posed (docs/poses.md says which models can)");
  CHECK(pose_body(rigid, "rigid", {}, Pose{}) == rigid.vertices({}));
}

TEST_CASE("draw_free_pose draws reproducibly and only poses the body stays clear in", "[bodies][pose]") {
  const Eigen::VectorXd shape = shape_of(30, 1.75, 0);
  Rng a(7), b(7);
  const DrawnPose first = draw_free_pose(posed_model(), shape, a);
  const DrawnPose again = draw_free_pose(posed_model(), shape, b);
  CHECK(first.pose.angles == again.pose.angles);
  CHECK(first.vertices == again.vertices);
  CHECK(first.redraws == again.redraws);
  CHECK(first.pose.angles.size() == posed_model().pose_angles().size());
  CHECK(first.vertices == posed_model().posed(shape, first.pose));
  CHECK(describe_pose_crossings(posed_model(), shape, first.pose, first.vertices).empty());
  CHECK(first.pull == 1.0);
}

TEST_CASE("a body that no pose of the space leaves clear gets a draw pulled towards its rest pose", "[bodies][pose]") {
  // Arms drawn down to 0-2 degrees of abduction pass through the trunk of a
  // woman of BMI 30 (refused by name in the test above), as a short woman near
  // BMI 60 did at every draw of the full space (pose-space sample 1044).
  const Eigen::VectorXd shape = shape_of(30, 1.75, 0);
  const std::vector<PoseAngle> space =
      with_sampling_ranges(posed_model().pose_angles(), "shoulder_abduction=0:2", "test");
  Rng rng(3);
  const DrawnPose drawn = draw_free_pose(posed_model(), shape, rng, 10, &space);
  CHECK(drawn.redraws >= 10);
  CHECK(drawn.pull < 1.0);
  CHECK(describe_pose_crossings(posed_model(), shape, drawn.pose, drawn.vertices).empty());
  // The arms between the rest pose's and the drawn 0-2 degrees, by the pull.
  const double rest = posed_model().rest_pose(shape).get("left_shoulder_abduction", 0.0);
  const double got = drawn.pose.get("left_shoulder_abduction", rest);
  CHECK(got < rest);
  CHECK(got >= rest + drawn.pull * (0.0 - rest) - 1e-9);
  CHECK(got <= rest + drawn.pull * (2.0 - rest) + 1e-9);
}

TEST_CASE("poses are drawn only from a space with a sampling range", "[bodies][pose]") {
  std::vector<PoseAngle> space = {{"a", -180, 180, 0, 0, ""}, {"b", -180, 180, 5, 5, ""}};
  CHECK_THROWS_WITH(check_drawable(space, "smpl"), Catch::Contains("body model 'smpl' has no pose distribution"));
  space[1].sample_hi = 6;
  CHECK_NOTHROW(check_drawable(space, "smpl"));
  CHECK_NOTHROW(check_drawable(human_pose_angles(), "parametric"));
}

TEST_CASE("a sampling range with a NaN bound is named as NaN", "[bodies][pose]") {
  // It was "range nan:90: expected lo <= hi" (an outside check).
  const std::vector<PoseAngle> space = human_pose_angles();
  CHECK_THROWS_WITH(with_sampling_ranges(space, "shoulder_abduction=nan:90", "--pose-range"),
                    Catch::Contains("--pose-range: left_shoulder_abduction is NaN; expected a number in"));
  CHECK_THROWS_WITH(with_sampling_ranges(space, "shoulder_abduction=90:30", "--pose-range"),
                    Catch::Contains("range 90:30: expected lo <= hi"));
}
