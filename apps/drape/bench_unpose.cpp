// `drape bench unpose`: how well, and how fast, the pose is read off a body
// mesh given posed (pose_fit.hpp, through unpose_given_body as predict and
// simulate use it). Bodies drawn over the body space, each posed by a pose
// drawn from the pose space, turned about the vertical and moved, optionally
// with noise on every vertex (as a scan would have it); the angles and the
// body at rest read back are compared with those that made the mesh.
#include "bench.hpp"

#include <drape/bodies/body_space.hpp>
#include <drape/bodies/given_body.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/registry.hpp>
#include <drape/training/rng.hpp>

#include <Eigen/Geometry>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench unpose");
  opts.add_options()("bodies", po::value<int>()->default_value(12), "bodies drawn, each in a drawn pose")(
      "seed", po::value<unsigned>()->default_value(0), "random seed of the bodies, poses, turns and noise")(
      "noise", po::value<double>()->default_value(0.0), "Gaussian noise added to every vertex, m (a scan's: 0.002)")(
      "rig", po::value<std::string>()->default_value("human"), "the parametric body's rig: human or mannequin");
  po::variables_map vm;
  if (!parse("drape bench unpose [--bodies 12] [--seed 0] [--noise 0.002] [--rig human]", args, opts, {}, vm)) return 0;
  const int count = vm["bodies"].as<int>();
  if (count < 1) throw UsageError("--bodies: expected at least 1");
  const double noise = vm["noise"].as<double>();
  if (!(noise >= 0 && noise < 0.05)) throw UsageError("--noise: expected 0 to 0.05 m");

  const Registry& registry = Registry::load_default(plugin_path(vm));
  const PluginDescriptor& d = registry.get("parametric");
  ParamValues values;
  values["rig"] = ParamValue{YAML::Node(vm["rig"].as<std::string>()), {"--rig", 0}};  // (named in its errors, not "<unknown>")
  const auto model = registry.create_body("parametric", Params(d.params, values, "body parametric"));
  const GivenBodyFrame frame(*model);
  frame.anchor(), frame.mean();  // found once, not timed with the first body

  Rng rng(vm["seed"].as<unsigned>());
  std::mt19937_64 gaussian_engine(vm["seed"].as<unsigned>());
  std::normal_distribution<double> gaussian(0.0, noise);
  BodySpace space;
  std::printf("%3s %6s %6s %4s %8s | %-28s %9s | %9s %9s | %8s %7s\n", "#", "BMI", "height", "sex", "turn deg", "worst angle",
              "error deg", "rest mean", "rest max", "fit rms", "s");
  std::vector<double> worst_angles, mean_angles, rest_means, rest_maxes, seconds;
  for (int i = 0; i < count; ++i) {
    BodyRequest request = draw_body(space, *model, rng);
    const Eigen::VectorXd shape = solve_in_space(*model, request);
    const DrawnPose drawn = draw_free_pose(*model, shape, rng);
    const Eigen::MatrixX3d rest = model->vertices(shape);
    const Pose truth = full_pose(*model, drawn.pose, rest);
    const double turn = rng.uniform(-180.0, 180.0);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(turn * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::RowVector3d offset(rng.uniform(-1.0, 1.0), rng.uniform(-0.02, 0.02), rng.uniform(-1.0, 1.0));
    Eigen::MatrixX3d given = (drawn.vertices * r.transpose()).rowwise() + offset;
    if (noise > 0)
      for (Eigen::Index v = 0; v < given.rows(); ++v)
        for (int c = 0; c < 3; ++c) given(v, c) += gaussian(gaussian_engine);

    Eigen::MatrixX3d body = given;
    const auto start = std::chrono::steady_clock::now();
    const GivenPosedBody read = unpose_given_body(body, *model, frame, "body");
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

    double worst = 0, sum = 0;
    std::string which;
    for (const auto& [name, degrees] : truth.angles) {
      const double e = std::abs(read.fit.pose.get(name, std::nan("")) - degrees);
      sum += e;
      if (!(e <= worst)) worst = e, which = name;
    }
    // The body at rest where the mesh stood, against the body that made it, moved as the mesh was.
    const Eigen::MatrixX3d expected = (rest * r.transpose()).rowwise() + offset;
    const Eigen::VectorXd miss = (read.moved.back(body) - expected).rowwise().norm();
    worst_angles.push_back(worst);
    mean_angles.push_back(sum / static_cast<double>(truth.angles.size()));
    rest_means.push_back(miss.mean());
    rest_maxes.push_back(miss.maxCoeff());
    std::printf("%3d %6.1f %6.2f %4.0f %8.1f | %-28s %9.3f | %6.2f mm %6.2f mm | %5.2f mm %7.2f\n", i, request.bmi,
                request.height, request.sex, turn, which.c_str(), worst, 1e3 * rest_means.back(), 1e3 * rest_maxes.back(),
                1e3 * read.fit.fit_rms, seconds.back());
    std::fflush(stdout);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  auto largest = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
  std::printf("over %d bodies (noise %.1f mm): worst angle error median %.3f, largest %.3f degrees; mean angle error "
              "median %.3f degrees; body at rest median %.2f mm mean, largest %.2f mm; time median %.2f s, largest %.2f s "
              "(wall, every core)\n",
              count, 1e3 * noise, median(worst_angles), largest(worst_angles), median(mean_angles),
              1e3 * median(rest_means), 1e3 * largest(rest_maxes), median(seconds), largest(seconds));
  return 0;
}

const RegisterBench registration{{"unpose", "read poses off posed body meshes: accuracy against the drawn pose, and time",
                                  run}};

}  // namespace
}  // namespace drape::cli
