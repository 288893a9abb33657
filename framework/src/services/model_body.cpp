// model_body_batch and prepare_bodies (services/model_body.hpp).
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/services/model_body.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

namespace drape {
namespace {

// A batch of several bodies says which one a notice is about.
std::string about(const SampleBatch& batch, int i) { return batch.size() > 1 ? "body " + std::to_string(i) + ": " : ""; }

// The shape is what the network knows; where the body stands is only a
// translation. Draped where the training bodies stood, the garment then
// moves back with the body: the same drape as for the body placed right.
Eigen::RowVector3d place(const Model& model, const ModelDomain& domain, SampleBatch& batch, int i,
                         std::vector<Notice>& notices) {
  Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  const std::optional<Eigen::Vector3d> offset = move_to_placement(domain, body);
  if (!offset) return Eigen::RowVector3d::Zero();
  batch.body.mat(i) = body.cast<float>();
  char where[160];
  std::snprintf(where, sizeof where, "%s's training bodies stood (centred in x and z, soles at y = %.3f)",
                model.file().filename().string().c_str(), domain.placement[1]);
  const std::string who = batch.size() > 1 ? "body " + std::to_string(i) : "the body";
  notices.push_back({Notice::Level::note, who + " " + placement_note(*offset, where)});
  return offset->transpose();
}

void check_domain(const Model& model, const ModelDomain& domain, const SampleBatch& batch, int i, bool strict,
                  const std::string& strict_option, std::vector<Notice>& notices) {
  const std::string name = model.file().filename().string();
  const Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  Eigen::VectorXd params;
  if (batch.body_params.size() > 0) params = batch.body_params.mat(i).row(0).transpose().cast<double>();
  const std::vector<std::string> outside =
      domain_violations(domain, body, model.assets().body.faces, params.size() ? &params : nullptr);
  if (outside.empty()) return;
  if (strict) {
    std::string all;
    for (const std::string& why : outside) all += (all.empty() ? "" : "; ") + why;
    throw ConfigError(strict_option + ": " + about(batch, i) + "the body is outside the model's training domain (" + all + ")");
  }
  for (const std::string& why : outside)
    notices.push_back({Notice::Level::warning, about(batch, i) + "the body is outside what " + name + " was trained on: " + why});
  notices.push_back({Notice::Level::warning, about(batch, i) + "the prediction may be wrong without showing it (" +
                                                 strict_option + " refuses such a body)"});
}

void note_fit(const Model& model, double garment_loop, const SampleBatch& batch, int i, std::vector<Notice>& notices) {
  const double ease = garment_ease(garment_loop, batch.body.mat(i).cast<double>(), model.assets().body.faces);
  if (!(ease < kMinimumEase)) return;  // fits, or not measurable (NaN)
  char line[400];
  std::snprintf(line, sizeof line,
                "the model's garment is %.1f %% smaller around than this body's chest or belly (the tailor's "
                "rule of docs/garments.md); simulated, a garment that small rides up over the belly or is stretched "
                "onto the body, and the model predicts it so. A larger size fits (drape simulate with size: auto)",
                -100.0 * ease);
  notices.push_back({Notice::Level::note, about(batch, i) + line});
}

}  // namespace

SampleBatch model_body_batch(const Model& model, const ModelBodyInput& input) {
  if (input.vertices.has_value() == input.request.has_value())
    throw ConfigError("a body: give either its vertices or a request for the model's body plugin");
  SampleBatch batch;
  if (input.vertices) {
    Mesh given;
    given.vertices = *input.vertices;
    require_vertex_count(given, model.assets().body.num_vertices(), input.name,
                         "the model's body model '" + model.assets_spec().body_model + "' has that many");
    check_body_units(given.vertices, "body " + input.name);
    if (model.needs_body_params())
      throw ConfigError("this model's graph takes the body parameters (input body_params), which a mesh does not "
                        "give: use --bmi");
    batch.body = Tensor(1, given.num_vertices(), 3);
    batch.body.mat(0) = given.vertices.cast<float>();
  } else {
    batch = model.body_for(*input.request);
  }
  // A model trained on several garment sizes takes the size as an input (garment_size_flag).
  if (model.needs_input("garment_size")) {
    if (!input.garment_size)
      throw ConfigError("this model was trained on several garment sizes (input garment_size): give --garment-size, one of " +
                        garment_size_choices());
    batch.garment_size = Tensor(1, 1, 1);
    batch.garment_size(0, 0, 0) = garment_size_flag(*input.garment_size);
  }
  return batch;
}

BodyPreparation::BodyPreparation(const Model& model, std::optional<ModelDomain> domain)
    : model_(model), domain_(std::move(domain)), garment_loop_(std::numeric_limits<double>::quiet_NaN()) {
  // A model of several sizes takes the size from its user: no fit to note.
  if (!model.needs_input("garment_size")) {
    const Assets& a = model.assets();
    garment_loop_ = garment_girth(a.garment->mesh.vertices, a.garment->mesh.faces, a.body.vertices);
  }
}

PreparedBodies BodyPreparation::prepare(SampleBatch& batch, bool strict, const std::string& strict_option,
                                        bool measure) const {
  PreparedBodies out;
  out.moved_by.assign(static_cast<std::size_t>(batch.size()), Eigen::RowVector3d::Zero());
  if (measure && !domain_ && !model_.file().empty()) {  // an untrained model in memory has no file to record one in
    const std::string name = model_.file().filename().string();
    if (strict)
      throw ConfigError(strict_option + ": " + model_.file().string() + " records no training domain to check the body against");
    out.notices.push_back({Notice::Level::note, name + " records no training domain, so a body outside it cannot be "
                                                       "told (drape model domain adds it)"});
  }
  for (int i = 0; i < batch.size(); ++i) {
    if (domain_) {
      out.moved_by[static_cast<std::size_t>(i)] = place(model_, *domain_, batch, i, out.notices);
      if (measure) check_domain(model_, *domain_, batch, i, strict, strict_option, out.notices);
    }
    if (measure && std::isfinite(garment_loop_)) note_fit(model_, garment_loop_, batch, i, out.notices);
  }
  return out;
}

}  // namespace drape
