#include "model_body.hpp"
#include "pose_options.hpp"

#include <drape/io/shipped_files.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/services/model_body.hpp>

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace drape::cli {

namespace fs = std::filesystem;

namespace {

ModelBodyInput body_input(const po::variables_map& vm) {
  if (vm.count("body") && (vm.count("height") || vm.count("sex") || vm.count("girth")))
    throw UsageError("--height, --sex and --girth go with --bmi; --body gives the body itself");
  ModelBodyInput input;
  if (vm.count("body")) {
    input.name = vm["body"].as<std::string>();
    const Mesh mesh = read_mesh(input.name);
    input.vertices = mesh.vertices;
    input.faces = mesh.faces;
  } else {
    BodyRequest request;
    request.bmi = vm["bmi"].as<double>();
    if (vm.count("height")) request.height = vm["height"].as<double>();
    if (vm.count("sex")) request.sex = vm["sex"].as<double>();
    request.proportions = parse_girths(vm);
    input.request = request;
  }
  if (vm.count("garment-size")) input.garment_size = vm["garment-size"].as<std::string>();
  if (vm.count("garment-grade")) input.garment_grade = vm["garment-grade"].as<double>();
  return input;
}

}  // namespace

void add_model_body_options(po::options_description& options, const std::string& body_help) {
  options.add_options()("body", po::value<std::string>(), body_help.c_str())(
      "strict", "refuse (exit 2) a body outside the model's training domain instead of warning")(
      "bmi", po::value<double>(), "or make the body with the model's body plugin: target BMI")(
      "height", po::value<double>(), "with --bmi: height in m (default 1.75)")(
      "sex", po::value<double>(), "with --bmi: 0 female ... 1 male (default 1)")(
      "garment-size", po::value<std::string>(),
      ("the garment's size: for a model of drapes in each body's own size, one of its sizes (drape model info lists "
       "them) or auto, the default: the size the tailor's rule gives the body (docs/garments.md); for a model trained "
       "on a few sizes: " + garment_size_choices()).c_str())(
      "garment-grade", po::value<double>(),
      "for a model of drapes in each body's own size: the garment's grade as a number (its girth over the design size's) "
      "instead of a size");
  add_girth_option(options, "with --bmi: ");
  options.add_options()(
      "pose", po::value<std::string>(),
      "for a model of posed drapes: the body's pose, name=degrees,... (docs/poses.md); the body given or made is "
      "taken as unposed")("pose-file", po::value<std::string>(), "the same from a YAML map of joint angle names to degrees")(
      "smpl-theta", po::value<std::string>(), "the same as SMPL's θ from a text file (SMPL body models)");
}

bool pose_given(const po::variables_map& vm) {
  return vm.count("pose") + vm.count("pose-file") + vm.count("smpl-theta") > 0;
}

std::string model_file_or_default(const po::variables_map& vm) {
  if (vm.count("model")) return find_input_file(vm["model"].as<std::string>()).string();  // models/... from anywhere
  // A posed body goes to the shipped model of posed drapes (the A-pose model
  // refuses a pose); DRAPE_MODEL, when set, names the one model for both.
  const char* env = std::getenv("DRAPE_MODEL");
  if (pose_given(vm) && !(env && *env))
    if (const fs::path file = shipped_model_path(posed_model_name); !file.empty()) return file.string();
  const std::string file = default_model_path().string();
  if (file.empty())
    throw UsageError(std::string("no --model given and the shipped model (models/") + kDefaultModelFile + ") was not found: give "
                     "--model FILE from drape train, or set DRAPE_MODEL");
  return file;
}

SampleBatch model_body(const Model& model, const po::variables_map& vm, BodyMove* moved_by,
                       std::vector<std::string>* printed) {
  SampleBatch batch = model_body_batch(model, body_input(vm));
  const BodyPreparation preparation(model, read_domain(model.file()));
  PreparedBodies prepared = preparation.prepare(batch, vm.count("strict") > 0, "--strict", true, vm.count("body") > 0);
  // Posed after the body is measured and placed at rest (a raised arm is no girth).
  const std::optional<Pose> pose = pose_options(vm, model.body_model(), model.assets_spec().body_model);
  for (Notice& n : preparation.pose(batch, pose ? *pose : Pose{}, vm.count("strict") > 0))
    prepared.notices.push_back(std::move(n));
  for (const Notice& n : prepared.notices) {
    const std::string line = (n.level == Notice::Level::note ? "note: " : "warning: ") + n.text;
    std::cerr << line << "\n";
    if (printed) printed->push_back(line);
  }
  if (moved_by) *moved_by = prepared.moved_by.front();
  return batch;
}

}  // namespace drape::cli
