// `drape body`: solve a body model for a BMI and height and write its mesh, or
// draw many bodies uniformly in BMI (as the seed's data set does).
#include "command.hpp"
#include "pose_options.hpp"
#include "sample_ranges.hpp"

#include <drape/bodies/body.hpp>
#include <drape/bodies/given_body.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/bodies/body_space.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/bodies/smpl_theta.hpp>
#include <drape/scene/body_overlap.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/index_locality.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/registry.hpp>
#include <drape/services/model_body.hpp>
#include <drape/training/rng.hpp>
#include <drape/io/svg_figure.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

struct Measured {
  double bmi, height;
};

Measured measure(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) { return {geometry::body_bmi(v, f), geometry::body_height(v)}; }

Mesh body_mesh(const BodyModel& body, const Eigen::VectorXd& shape) {
  Mesh m;
  m.vertices = body.vertices(shape);
  m.faces = body.faces();
  return m;
}

// A body asked for by hand is written as asked, but a body that passes
// through itself has no inside there: said, with where, since a scene refuses
// it under the garment.
void warn_if_self_intersecting(const Mesh& mesh, bool with_girths) {
  const std::string where = describe_self_intersections(mesh.vertices, mesh.faces);
  if (where.empty()) return;
  std::cerr << "warning: this body passes through itself: " << where << "; a scene refuses it where the garment lies"
            << (with_girths ? ". These girths clash (drape generate and --sample halve such girths towards the mean build)" : "")
            << "\n";
}

// --param name=value ... for the body plugin.
ParamValues plugin_params(const po::variables_map& vm) {
  ParamValues values;
  if (vm.count("param"))
    for (const auto& item : vm["param"].as<std::vector<std::string>>()) {
      const auto eq = item.find('=');
      if (eq == std::string::npos || eq == 0) throw UsageError("--param wants name=value, got '" + item + "'");
      if (values.count(item.substr(0, eq)))
        throw UsageError("--param " + item.substr(0, eq) + " is given twice; give each parameter once");
      values[item.substr(0, eq)] = {YAML::Load(item.substr(eq + 1)), {"--param", 0}};
    }
  return values;
}

// The body plugin, loaded (and how long that took).
struct LoadedBody {
  std::string model;
  std::unique_ptr<BodyModel> body;
  double load_s;
};

// Any pose option on a model without a skeleton: refused, naming the model
// (and the model's own reason when it has one: an SMPL file without its pose
// datasets).
void require_poseable(const po::variables_map& vm, const LoadedBody& loaded) {
  if (!(vm.count("pose") || vm.count("pose-file") || vm.count("poses") || vm.count("smpl-theta")) || loaded.body->poseable())
    return;
  const std::string reason = unposeable_reason(*loaded.body);
  if (!reason.empty()) throw ConfigError("body " + loaded.model + ": " + reason);
  throw ConfigError("body " + loaded.model + " has no skeleton, so it cannot be posed (--pose, --pose-file, --poses, "
                    "--smpl-theta); docs/poses.md says which models can");
}

// One body, solved for --bmi, --height and --sex (and posed by --pose): its
// shape and measurements printed, its mesh written to --out.
int solve_one(const po::variables_map& vm, const LoadedBody& loaded, const Range& bmi) {
  const BodyModel& body = *loaded.body;
  const auto names = body.shape_names();
  if (bmi.lo != bmi.hi) throw UsageError("--bmi: a range needs --sample");
  const Range height = vm.count("height") ? parse_range("height", vm["height"].as<std::string>()) : Range{1.75, 1.75};
  if (height.lo != height.hi) throw UsageError("--height: a range needs --sample");
  const double sex = vm.count("sex") ? vm["sex"].as<double>() : 1.0;
  const auto t1 = std::chrono::steady_clock::now();
  const BodyRequest request{bmi.lo, height.lo, sex, parse_girths(vm)};
  const Pose pose = pose_options(vm, body, loaded.model).value_or(Pose{});
  const Eigen::VectorXd shape = body.solve(request);
  const double solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  Mesh mesh = body_mesh(body, shape);
  const Measured got = measure(mesh.vertices, mesh.faces);
  const auto loc = geometry::index_locality(mesh.faces, mesh.num_vertices());
  std::cout << std::setprecision(6) << "body " << loaded.model << " (load " << loaded.load_s << " s, solve " << solve_s
            << " s)\n";
  for (std::size_t i = 0; i < names.size(); ++i) std::cout << "  " << names[i] << " = " << shape[static_cast<Eigen::Index>(i)] << "\n";
  // (Of the body at rest: a posed body's height is no stature, as a knee
  // bent 115 degrees stands 1.13 m of a 1.50 m woman.)
  std::cout << "measured BMI " << got.bmi << " (requested " << bmi.lo << "), height " << got.height << " m (requested "
            << height.lo << ")" << (pose.empty() ? "" : ", at rest before the pose") << "\n"
            << "vertices " << mesh.num_vertices() << ", faces " << mesh.num_faces() << "\n"
            << "consecutive indices that are mesh neighbours: " << 100 * loc.one_hop << "%, within two hops "
            << 100 * loc.two_hop << "%\n";
  warn_if_self_intersecting(mesh, !request.proportions.empty());
  if (!pose.empty()) {
    mesh.vertices = pose_body(body, loaded.model, shape, pose);
    // The rest pose's angles that are not 0 (the A-pose's shoulder abduction)
    // tell what an angle left out means.
    Pose rest_nonzero;
    for (const auto& [name, degrees] : body.rest_pose(shape).angles)
      if (degrees != 0 && !pose.angles.count(name)) rest_nonzero.angles[name] = degrees;
    std::cout << "posed: " << format_pose(pose) << "; every other angle at rest"
              << (rest_nonzero.empty() ? "" : " (" + format_pose(rest_nonzero) + ")") << "\n";
  }
  if (vm.count("out")) {
    write_mesh(vm["out"].as<std::string>(), mesh);
    std::cout << "wrote " << vm["out"].as<std::string>() << "\n";
  }
  return 0;
}

// The body space --sample draws from: --bmi, --height, --sex and --girths.
BodySpace sample_space(const po::variables_map& vm, const Range& bmi, const Range& height) {
  BodySpace space;
  space.bmi_lo = bmi.lo;
  space.bmi_hi = bmi.hi;
  space.height_lo = height.lo;
  space.height_hi = height.hi;
  if (vm.count("sex")) space.sex_lo = space.sex_hi = vm["sex"].as<double>();
  space.proportion_spread = vm["girths"].as<double>();
  if (!(space.proportion_spread >= 0 && space.proportion_spread <= 1)) throw UsageError("--girths: expected a fraction in [0, 1]");
  if (vm.count("girth")) throw UsageError("--girth holds one body's proportions; --sample draws them (--girths sets their spread)");
  return space;
}

SvgLayer skin_of(const Mesh& mesh) {
  SvgLayer skin;
  skin.vertices = mesh.vertices;
  skin.faces = mesh.faces;
  skin.colour = "#d9a384";
  skin.cull_back_faces = true;
  return skin;
}

// The --bmi and --height ranges of --sample against what the model
// reaches: BMI by its range, the heights by solving the mean build at both
// ends (a model says its reachable heights only when asked for a body).
void check_sample_ranges(const BodyModel& body, const std::string& model, const Range& bmi, const Range& height) {
  const auto [lightest, heaviest] = body.bmi_range();
  if (bmi.lo < lightest || bmi.hi > heaviest) {
    std::ostringstream m;
    m << "--bmi " << bmi.lo << ":" << bmi.hi << " reaches outside what body " << model << " makes, BMI " << lightest
      << " to " << heaviest;
    throw UsageError(m.str());
  }
  const BodyRequest mean = body.mean_request();
  for (const double h : {height.lo, height.hi}) {
    try {
      body.solve(BodyRequest{std::clamp(mean.bmi, bmi.lo, bmi.hi), h, mean.sex, {}});
    } catch (const ConfigError& e) {
      std::ostringstream m;
      m << "--height " << height.lo << ":" << height.hi << ": " << e.what();
      throw UsageError(m.str());
    }
  }
}

// --sample N: bodies drawn from the space, written to --out-dir with
// bodies.csv (and the first 16 drawn side by side into --svg).
int sample_many(const po::variables_map& vm, const LoadedBody& loaded, const Range& bmi) {
  const BodyModel& body = *loaded.body;
  const auto names = body.shape_names();
  const int count = vm["sample"].as<int>();
  if (count < 1) throw UsageError("--sample " + std::to_string(count) + ": expected at least 1");
  if (!vm.count("out-dir")) throw UsageError("--sample needs --out-dir");
  if (vm.count("out")) throw UsageError("--out writes one body; --sample writes its bodies into --out-dir");
  // Everything that can be refused is, before anything is written: the
  // ranges against what the model reaches (not only the values drawn), and
  // the folder.
  if (vm.count("poses")) check_drawable(body.pose_angles(), loaded.model);
  const std::filesystem::path dir = vm["out-dir"].as<std::string>();
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir))
    throw UsageError("--out-dir " + dir.string() + " is a file, not a folder");
  const Range height = vm.count("height") ? parse_range("height", vm["height"].as<std::string>()) : Range{1.5, 2.0};
  const BodySpace space = sample_space(vm, bmi, height);
  check_sample_ranges(body, loaded.model, bmi, height);
  std::filesystem::create_directories(dir);
  Rng rng(vm["seed"].as<unsigned>());
  // Poses come from their own stream, so the shapes of a seed are the same
  // with --poses as without.
  const bool poses = vm.count("poses") > 0;
  Rng pose_rng(Rng::derive(vm["seed"].as<unsigned>(), "poses"));
  const std::vector<PoseAngle> angles = poses ? body.pose_angles() : std::vector<PoseAngle>{};
  std::ostringstream csv;
  csv << std::setprecision(10) << "index,file,requested_bmi,requested_height,sex";
  for (const auto& n : names) csv << ",shape_" << n;
  csv << ",girth_halvings,measured_bmi,measured_height,self_intersections";
  for (const auto& a : angles) csv << ",pose_" << a.name;
  csv << (poses ? ",pose_redraws\n" : "\n");
  int redrawn_total = 0;
  double worst = 0;
  int intersecting = 0, halved = 0;
  SvgFigure figure("drape body --sample: BMI " + std::to_string(bmi.lo).substr(0, 4) + "-" + std::to_string(bmi.hi).substr(0, 4) +
                   ", height " + std::to_string(height.lo).substr(0, 4) + "-" + std::to_string(height.hi).substr(0, 4) +
                   " m, girth spread " + std::to_string(space.proportion_spread).substr(0, 4) +
                   (vm.count("poses") ? ", poses drawn (docs/poses.md)" : ""));
  constexpr int kDrawn = 16;
  for (int i = 0; i < count; ++i) {
    BodyRequest request = draw_body(space, body, rng);
    int halvings = 0;
    const Eigen::VectorXd shape = solve_in_space(body, request, &halvings);
    Mesh mesh = body_mesh(body, shape);
    const Measured got = measure(mesh.vertices, mesh.faces);
    const std::size_t crossing = geometry::self_intersections(mesh.vertices, mesh.faces, 10).size();
    Pose pose;
    int redraws = 0;
    if (poses) {
      DrawnPose drawn = [&] {
        try {
          return draw_free_pose(body, shape, pose_rng);
        } catch (const Error& e) {
          throw Error("drape body --sample: body " + std::to_string(i) + ": " + e.what());
        }
      }();
      pose = std::move(drawn.pose);
      mesh.vertices = std::move(drawn.vertices);
      redraws = drawn.redraws;
      redrawn_total += redraws;
    }
    char file[32];
    std::snprintf(file, sizeof file, "body_%05d.obj", i);
    write_mesh(dir / file, mesh);
    csv << i << "," << file << "," << request.bmi << "," << request.height << "," << request.sex;
    for (Eigen::Index k = 0; k < shape.size(); ++k) csv << "," << shape[k];
    csv << "," << halvings << "," << got.bmi << "," << got.height << "," << crossing;
    for (const auto& a : angles) csv << "," << pose.angles.at(a.name);
    if (poses) csv << "," << redraws;
    csv << "\n";
    worst = std::max(worst, std::abs(got.bmi - request.bmi));
    intersecting += crossing > 0;
    halved += halvings > 0;
    if (vm.count("svg") && i < kDrawn) {
      char caption[96];
      std::snprintf(caption, sizeof caption, "%s, %.2f m, BMI %.1f", request.sex < 0.5 ? "F" : "M", got.height, got.bmi);
      figure.add_panel({caption, {skin_of(mesh)}});
    }
  }
  if (vm.count("svg")) {
    figure.write(vm["svg"].as<std::string>());
    std::cout << "wrote " << vm["svg"].as<std::string>() << "\n";
  }
  write_atomically(dir / "bodies.csv", [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    out << csv.str();
    if (!out) throw Error("cannot write " + tmp.string());
  });
  std::cout << "wrote " << count << (count == 1 ? " body" : " bodies") << " and bodies.csv to " << dir.string()
            << " (worst |BMI error| " << worst << "; " << intersecting << " self-intersecting; " << halved
            << " with girths halved to reach their BMI or to clear a self-intersection";
  if (poses) std::cout << "; posed, " << redrawn_total << " poses drawn again because the body passed through itself";
  std::cout << ")\n";
  return 0;
}

// For a mesh of another vertex count than the body model's: the plugin's
// other rigs (its `rig` parameter's choices) that make bodies of that count,
// as "; the human rig's bodies have 6904: add --param rig=human" ("" when
// none does). Only on the error's path: each rig is built to be counted.
std::string other_rig_hint(const po::variables_map& vm, const std::string& model, Eigen::Index count) {
  const Registry& reg = Registry::load_default(plugin_path(vm));
  const PluginDescriptor& d = reg.get(model);
  const auto rig = std::find_if(d.params.begin(), d.params.end(), [](const ParamSpec& p) { return p.name == "rig"; });
  if (rig == d.params.end()) return "";
  for (const std::string& choice : rig->choices) {
    ParamValues values = plugin_params(vm);
    values["rig"] = {YAML::Node(choice), {"--param", 0}};
    try {
      if (reg.create_body(model, Params(d.params, values, "body " + model))->num_vertices() == count)
        return "; the " + choice + " rig's bodies have " + std::to_string(count) + ": --param rig=" + choice;
    } catch (const std::exception&) {
      // a rig that cannot be built here is no hint
    }
  }
  return "";
}

// --unpose FILE: a body mesh given posed, told apart into its pose and its
// body at rest (pose_fit.hpp): the angles printed (and written to
// --pose-out, a pose file --pose-file reads), the body at rest written to
// --out where, and as, the mesh stood.
int unpose_one(const po::variables_map& vm, const LoadedBody& loaded) {
  const BodyModel& body = *loaded.body;
  if (!body.poseable())
    throw ConfigError("drape body --unpose: body " + loaded.model + " has no skeleton, so no pose can be read off a mesh");
  const std::string file = vm["unpose"].as<std::string>();
  const Mesh given = read_mesh(file);
  require_vertex_count(given, body.num_vertices(), file,
                       "body " + loaded.model + " has that many" +
                           (given.num_vertices() == body.num_vertices() ? "" : other_rig_hint(vm, loaded.model, given.num_vertices())));
  check_body_units(given.vertices, "body " + file);
  const GivenBodyFrame frame(body);
  // A mirrored, re-indexed or spiked mesh has no pose to read: refused as predict and simulate refuse it.
  require_body_model_mesh(given.vertices, &given.faces, frame.mean(), body.faces(), "body " + file);
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::MatrixX3d rest = given.vertices;
  const GivenPosedBody unposed = unpose_given_body(rest, body, frame, "body " + file);
  // (A rest body of the wrong height was written with exit 0.)
  if (!unposed.outside.empty()) throw ConfigError(unposed.outside);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Pose rounded;  // to a hundredth of a degree, within the ranges the angles were fitted in
  for (const auto& [name, degrees] : unposed.fit.pose.angles) rounded.angles[name] = std::round(degrees * 100.0) / 100.0 + 0.0;  // + 0: no -0
  std::printf("pose: %s\n", format_pose(rounded).c_str());
  std::printf("the body model posed so lies %.2f mm rms, %.2f mm at most, from the mesh; the mesh unposed poses back "
              "onto it to %.3f mm (%.2f s, %d Levenberg-Marquardt steps)\n",
              1e3 * unposed.fit.fit_rms, 1e3 * unposed.fit.fit_max, 1e3 * unposed.fit.reposed_error, seconds,
              unposed.fit.iterations);
  if (!unposed.turned.empty())
    std::printf("note: the mesh %s; the pose is read on it turned to face as they do, and the body at rest written "
                "turned back\n",
                facing_text(unposed.turn_degrees).c_str());
  if (!unposed.warning.empty()) std::cerr << "warning: " << unposed.warning << "\n";
  if (unposed.lean_degrees > kLeanToleranceDegrees)
    std::printf("note: the mesh stands %.1f degrees from upright as a whole (lying, or upside down); the body at rest is "
                "written as it stood (predict and simulate refuse a body leaning over %.0f degrees)\n",
                unposed.lean_degrees, kLeanLimitDegrees);
  if (vm.count("pose-out")) {
    std::ostringstream yaml;
    yaml << "# drape body --unpose " << file << ": joint angles in degrees (drape body/predict --pose-file)\n";
    for (const auto& [name, degrees] : rounded.angles) yaml << name << ": " << degrees << "\n";
    write_text_atomically(vm["pose-out"].as<std::string>(), yaml.str());
    std::printf("wrote %s\n", vm["pose-out"].as<std::string>().c_str());
  }
  if (vm.count("out")) {
    Mesh out = given;
    out.vertices = unposed.moved.back(rest);  // where the mesh stood, turned as it was
    write_mesh(vm["out"].as<std::string>(), out);
    std::printf("wrote %s (the body at rest)\n", vm["out"].as<std::string>().c_str());
  }
  return 0;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape body");
  opts.add_options()("model", po::value<std::string>()->default_value("parametric"), "body plugin")(
      "bmi", po::value<std::string>()->default_value("24"), "BMI, or a range lo:hi for --sample")(
      "height", po::value<std::string>(), "height in m, or a range (default 1.75; 1.5:2.0 with --sample)")(
      "sex", po::value<double>(), "0 female ... 1 male (default 1; random 0/1 with --sample)")(
      "out", po::value<std::string>(), "mesh file to write (.obj, .ply, .gltf, .glb)")(
      "sample", po::value<int>(), "draw this many bodies: BMI uniform in the --bmi range, sex, height and girths independently")(
      "girths", po::value<double>()->default_value(1.0),
      "with --sample: the spread of the girths, as a fraction of the model's range (0: the mean build)")(
      "seed", po::value<unsigned>()->default_value(0), "random seed for --sample")(
      "out-dir", po::value<std::string>(), "folder for --sample: body_00000.obj ... and bodies.csv")(
      "pose", po::value<std::string>(),
      "joint angles in degrees, name=value,... (shoulder_abduction=90,left_elbow_flexion=30; docs/poses.md)")(
      "pose-file", po::value<std::string>(), "joint angles from a YAML map of name: degrees")(
      "smpl-theta", po::value<std::string>(),
      "with --model smpl: SMPL's pose theta, 72 (root first, which must be 0) or 69 numbers in radians, text or .npy (docs/smpl.md)")(
      "poses", "with --sample: also draw a pose for each body, independently of its shape (docs/poses.md)")(
      "svg", po::value<std::string>(), "with --sample: also draw the first 16 bodies side by side (.svg, or .html: a 3D viewer)")(
      "unpose", po::value<std::string>(),
      "a body mesh given posed (the model's topology): print its pose, write it at rest to --out (docs/poses.md)")(
      "pose-out", po::value<std::string>(), "with --unpose: also write the pose as a pose file (YAML, for --pose-file)")(
      "param", po::value<std::vector<std::string>>()->composing(),
      "a parameter of the body plugin, name=value (repeatable), e.g. file=smpl.h5 for --model smpl");
  add_girth_option(opts, "");
  po::variables_map vm;
  const std::string usage =
      "drape body --bmi 38 --height 1.80 [--sex 1] [--out body.obj]\n"
      "       drape body --sample N --bmi 10:65 [--height 1.5:2.0] [--girths 1] [--seed S] [--poses] --out-dir DIR\n"
      "       drape body --bmi 30 --pose shoulder_abduction=90,elbow_flexion=45 --out posed.obj\n"
      "       drape body --model smpl --param file=smpl.h5 --bmi 30 --smpl-theta theta.txt --out posed.obj\n"
      "       drape body --param rig=human --unpose posed.obj [--pose-out pose.yaml] --out rest.obj";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  check_mesh_outputs(vm, {"out"});

  const Registry& reg = Registry::load_default(plugin_path(vm));
  LoadedBody loaded;
  loaded.model = vm["model"].as<std::string>();
  const PluginDescriptor& desc = reg.get(loaded.model);
  const auto t0 = std::chrono::steady_clock::now();
  const ParamValues values = plugin_params(vm);
  loaded.body = reg.create_body(loaded.model, Params(desc.params, values, "body " + loaded.model));
  loaded.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Range bmi = parse_range("bmi", vm["bmi"].as<std::string>());
  require_poseable(vm, loaded);
  if (vm.count("sample") && (vm.count("pose") || vm.count("pose-file") || vm.count("smpl-theta")))
    throw UsageError("--pose, --pose-file and --smpl-theta pose one body; --sample draws poses with --poses");
  if (vm.count("poses") && !vm.count("sample")) throw UsageError("--poses needs --sample");
  if (vm.count("pose-out") && !vm.count("unpose")) throw UsageError("--pose-out goes with --unpose");
  // An option given for another use of the command is refused, not ignored
  // (a value left at its default counts as not given).
  const auto given = [&](const char* option) { return vm.count(option) && !vm[option].defaulted(); };
  if (vm.count("unpose")) {
    for (const char* other : {"sample", "pose", "pose-file", "smpl-theta", "girth", "bmi", "height", "sex", "girths", "seed",
                              "out-dir", "svg"})
      if (given(other)) throw UsageError(std::string("--unpose reads the pose and the body off the mesh; leave out --") + other);
    return unpose_one(vm, loaded);
  }
  if (!vm.count("sample"))
    for (const char* other : {"out-dir", "svg", "girths", "seed"})
      if (given(other)) throw UsageError(std::string("--") + other + " goes with --sample (one body is written to --out)");
  return vm.count("sample") ? sample_many(vm, loaded, bmi) : solve_one(vm, loaded, bmi);
}

const RegisterCommand registration{{"body", "solve a body for BMI and height, or sample many bodies", run}};

}  // namespace
}  // namespace drape::cli
