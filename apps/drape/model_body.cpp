#include "model_body.hpp"

#include <drape/body_units.hpp>
#include <drape/garment_size.hpp>
#include <drape/mesh_io.hpp>
#include <drape/model_domain.hpp>

#include <cstdio>
#include <iostream>

namespace drape::cli {

namespace {

// A model trained on several garment sizes takes the size as an input (garment_size_flag).
void add_garment_size(const Model& model, const po::variables_map& vm, SampleBatch& batch) {
  if (!model.needs_input("garment_size")) return;
  if (!vm.count("garment-size"))
    throw ConfigError("this model was trained on several garment sizes (input garment_size): give --garment-size, one of " +
                      garment_size_choices());
  batch.garment_size = Tensor(1, 1, 1);
  batch.garment_size(0, 0, 0) = garment_size_flag(vm["garment-size"].as<std::string>());
}

SampleBatch body_of(const Model& model, const po::variables_map& vm) {
  SampleBatch batch;
  if (vm.count("body") && (vm.count("height") || vm.count("sex") || vm.count("girth")))
    throw UsageError("--height, --sex and --girth go with --bmi; --body gives the body itself");
  if (vm.count("body")) {
    const std::string file = vm["body"].as<std::string>();
    const Mesh given = read_mesh(file);
    require_vertex_count(given, model.assets().body.num_vertices(), file,
                         "the model's body model '" + model.assets_spec().body_model + "' has that many");
    check_body_units(given.vertices, "body " + file);
    if (model.needs_body_params())
      throw ConfigError("this model's graph takes the body parameters (input body_params), which a mesh does not "
                        "give: use --bmi");
    batch.body = Tensor(1, given.num_vertices(), 3);
    batch.body.mat(0) = given.vertices.cast<float>();
    return batch;
  }
  BodyRequest request;
  request.bmi = vm["bmi"].as<double>();
  if (vm.count("height")) request.height = vm["height"].as<double>();
  if (vm.count("sex")) request.sex = vm["sex"].as<double>();
  request.proportions = parse_girths(vm);
  return model.body_for(request);
}

}  // namespace

void add_model_body_options(po::options_description& options, const std::string& body_help) {
  options.add_options()("body", po::value<std::string>(), body_help.c_str())(
      "strict", "refuse (exit 2) a body outside the model's training domain instead of warning")(
      "bmi", po::value<double>(), "or make the body with the model's body plugin: target BMI")(
      "height", po::value<double>(), "with --bmi: height in m (default 1.75)")(
      "sex", po::value<double>(), "with --bmi: 0 female ... 1 male (default 1)")(
      "garment-size", po::value<std::string>(), ("for a model trained on several sizes: " + garment_size_choices()).c_str());
  add_girth_option(options, "with --bmi: ");
}

std::string model_file_or_default(const po::variables_map& vm) {
  if (vm.count("model")) return vm["model"].as<std::string>();
  const std::string file = default_model_path().string();
  if (file.empty())
    throw UsageError("no --model given and the shipped model (models/tshirt-coarse.h5) was not found: give "
                     "--model FILE from drape train, or set DRAPE_MODEL");
  return file;
}

SampleBatch model_body(const Model& model, const po::variables_map& vm, Eigen::RowVector3d* moved_by) {
  SampleBatch batch = body_of(model, vm);
  add_garment_size(model, vm, batch);
  const std::optional<ModelDomain> domain = read_domain(model.file());
  const Eigen::RowVector3d moved = place_like_training(model, domain, batch);
  if (moved_by) *moved_by = moved;
  check_domain(model, domain, batch, vm.count("strict") > 0);
  note_fit(model, batch);
  return batch;
}

Eigen::RowVector3d place_like_training(const Model& model, const std::optional<ModelDomain>& domain, SampleBatch& batch) {
  if (!domain) return Eigen::RowVector3d::Zero();
  // The shape is what the network knows; where the body stands is only a
  // translation. Draped where the training bodies stood, the garment then
  // moves back with the body: the same drape as for the body placed right.
  Eigen::MatrixX3d body = batch.body.mat(0).cast<double>();
  const std::optional<Eigen::Vector3d> offset = move_to_placement(*domain, body);
  if (!offset) return Eigen::RowVector3d::Zero();
  batch.body.mat(0) = body.cast<float>();
  char where[160];
  std::snprintf(where, sizeof where, "%s's training bodies stood (centred in x and z, soles at y = %.3f)",
                model.file().filename().string().c_str(), domain->placement[1]);
  std::cerr << "note: the body " << placement_note(*offset, where) << "\n";
  return offset->transpose();
}

void note_fit(const Model& model, const SampleBatch& batch) {
  if (model.needs_input("garment_size")) return;  // the size is the user's to give
  const Assets& a = model.assets();
  const double ease = garment_ease(a.garment->mesh.vertices, a.garment->mesh.faces, a.body.vertices,
                                   batch.body.mat(0).cast<double>(), a.body.faces);
  if (!(ease < kMinimumEase)) return;  // fits, or not measurable (NaN)
  char line[400];
  std::snprintf(line, sizeof line,
                "note: the model's garment is %.1f %% smaller around than this body's chest or belly (the tailor's "
                "rule of docs/garments.md); simulated, a garment that small rides up over the belly or is stretched "
                "onto the body, and the model predicts it so. A larger size fits (drape simulate with size: auto)\n",
                -100.0 * ease);
  std::cerr << line;
}

void check_domain(const Model& model, const std::optional<ModelDomain>& domain, const SampleBatch& batch, bool strict) {
  const std::string name = model.file().filename().string();
  if (!domain) {
    std::cerr << "note: " << name << " records no training domain, so a body outside it cannot be told (drape model "
              << "domain adds it)\n";
    if (strict) throw ConfigError("--strict: " + model.file().string() + " records no training domain to check the body against");
    return;
  }
  const Eigen::MatrixX3d body = batch.body.mat(0).cast<double>();
  Eigen::VectorXd params;
  if (batch.body_params.size() > 0) params = batch.body_params.mat(0).row(0).transpose().cast<double>();
  const std::vector<std::string> outside =
      domain_violations(*domain, body, model.assets().body.faces, params.size() ? &params : nullptr);
  if (outside.empty()) return;
  for (const std::string& why : outside)
    std::cerr << (strict ? "error" : "warning") << ": the body is outside what " << name << " was trained on: " << why << "\n";
  if (strict) throw ConfigError("--strict: the body is outside the model's training domain (" + outside.front() + ")");
  std::cerr << "warning: the prediction may be wrong without showing it (--strict refuses such a body)\n";
}

}  // namespace drape::cli
