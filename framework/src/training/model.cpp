// Trained models: the assets spec as text, graph inputs by name, loading and prediction.
#include <drape/vertex_count.hpp>
#include <drape/bodies/body.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/io/dataset.hpp>
#include <drape/training/model.hpp>
#include <drape/training/model_params.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/garment_sizes.hpp>
#include <drape/registry.hpp>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <iterator>
#include <utility>

namespace fs = std::filesystem;

namespace drape {
namespace {

const std::vector<std::string> kKnownInputs{"body",          "body_params",      "target", "garment_size",
                                            "garment_grade", "unposed_body",     "joint_transforms", "pose"};

// A parameter value as one line of flow YAML, as AssetsSpec::yaml() writes it.
std::string flow(const YAML::Node& node) {
  YAML::Emitter e;
  e << YAML::Flow << node;
  return e.c_str();
}

std::map<std::string, std::string> params_text(const ParamValues& values) {
  std::map<std::string, std::string> out;
  for (const auto& [k, v] : values) out[k] = flow(v.node);
  return out;
}

ParamValues param_values(const std::map<std::string, std::string>& text, const std::string& what) {
  ParamValues out;
  for (const auto& [k, v] : text) out[k] = {YAML::Load(v), {what, 0}};
  return out;
}

Tensor slice_tensor(const Tensor& t, int first, int count) {
  if (t.empty()) return {};
  Tensor out(count, t.rows(), t.cols());
  const std::size_t per = static_cast<std::size_t>(t.rows()) * static_cast<std::size_t>(t.cols());
  std::copy(t.data() + per * static_cast<std::size_t>(first), t.data() + per * static_cast<std::size_t>(first + count),
            out.data());
  return out;
}

}  // namespace

AssetsSpec parse_assets_spec(const std::string& yaml, const std::string& what) {
  AssetsSpec spec;
  try {
    const YAML::Node root = YAML::Load(yaml);
    if (!root.IsMap()) throw ConfigError(what + ": the assets spec is not a YAML map");
    auto text_map = [&](const YAML::Node& n, const char* key) {
      std::map<std::string, std::string> out;
      if (!n[key]) return out;
      if (!n[key].IsMap()) throw ConfigError(what + ": assets `" + key + "` is not a map");
      for (const auto& kv : n[key]) out[kv.first.as<std::string>()] = flow(kv.second);
      return out;
    };
    for (const auto& kv : root) {
      const auto key = kv.first.as<std::string>();
      if (key != "body" && key != "garment" && key != "levels" && key != "eigen_k" && key != "encoder_body")
        throw ConfigError(what + ": unknown assets key '" + key + "'");
    }
    if (!root["body"] || !root["body"]["model"] || !root["garment"] || !root["garment"]["template"])
      throw ConfigError(what + ": the assets spec must name body.model and garment.template");
    spec.body_model = root["body"]["model"].as<std::string>();
    spec.body_params = text_map(root["body"], "params");
    spec.garment = root["garment"]["template"].as<std::string>();
    spec.garment_params = text_map(root["garment"], "params");
    if (root["levels"]) spec.levels = root["levels"].as<int>();
    if (root["eigen_k"]) spec.eigen_k = root["eigen_k"].as<int>();
    if (root["encoder_body"]) {
      if (!root["encoder_body"]["model"]) throw ConfigError(what + ": assets `encoder_body` must name its model");
      spec.encoder_body = root["encoder_body"]["model"].as<std::string>();
      spec.encoder_body_params = text_map(root["encoder_body"], "params");
    }
  } catch (const YAML::Exception& e) {
    throw ConfigError(what + ": bad assets spec: " + e.what());
  }
  return spec;
}

AssetsSpec assets_spec_for(const Scene& scene, int eigen_k, int levels) {
  // A model's template is the garment its plugin builds; a graded garment's
  // drapes would be learnt against the wrong rest shape, so they are refused.
  if (scene.garment_grade != 1.0)
    throw ConfigError("the scene's garment is graded (grade " + std::to_string(scene.garment_grade) +
                      "); a model's garment template is ungraded, so a model cannot be made from its drapes yet "
                      "(grade the template's own sizes instead, e.g. the tshirt's size parameter)");
  AssetsSpec spec;
  spec.body_model = scene.body_model;
  spec.body_params = params_text(scene.body_params);
  spec.garment = scene.garment;
  spec.garment_params = params_text(scene.garment_params);
  // size: auto (a dataset of each body in its own size): the sizes share the
  // design size's mesh, and its garment is the template (the plugin's default size).
  if (garment_size_is_auto(scene)) spec.garment_params.erase("size");
  spec.eigen_k = eigen_k;
  spec.levels = levels;
  return spec;
}

SampleBatch SampleBatch::slice(int first, int count) const {
  SampleBatch out;
  out.body = slice_tensor(body, first, count);
  out.body_params = slice_tensor(body_params, first, count);
  out.target = slice_tensor(target, first, count);
  out.garment_size = slice_tensor(garment_size, first, count);
  out.garment_grade = slice_tensor(garment_grade, first, count);
  out.unposed_body = slice_tensor(unposed_body, first, count);
  out.joint_transforms = slice_tensor(joint_transforms, first, count);
  out.pose = slice_tensor(pose, first, count);
  return out;
}

std::map<std::string, int> graph_dims(const Assets& assets, int body_params) {
  auto dims = assets.dims();
  dims["body_params"] = body_params;
  return dims;
}

void check_graph_inputs(const GraphSpec& spec) {
  for (const auto& [name, shape] : spec.inputs)
    if (std::find(kKnownInputs.begin(), kKnownInputs.end(), name) == kKnownInputs.end())
      throw ConfigError(shape.second, "graph input '" + name + "' is not one drape feeds" + did_you_mean(name, kKnownInputs) +
                                          " (inputs: body [body_vertices, 3], body_params [1, body_params], target "
                                          "[garment_vertices, 3], garment_size [1, 1], garment_grade [1, 1], unposed_body "
                                          "[body_vertices, 3], joint_transforms [joints, 12], pose [1, pose_angles])");
}

std::map<std::string, Tensor> graph_inputs(const Graph& graph, const SampleBatch& batch, bool with_target) {
  std::map<std::string, Tensor> in;
  for (const auto& name : graph.input_names()) {
    const Tensor* t = name == "body"          ? &batch.body
                      : name == "body_params"  ? &batch.body_params
                      : name == "garment_size" ? &batch.garment_size
                      : name == "garment_grade" ? &batch.garment_grade
                      : name == "unposed_body" ? &batch.unposed_body
                      : name == "joint_transforms" ? &batch.joint_transforms
                      : name == "pose"         ? &batch.pose
                                                : &batch.target;
    if (name == "target" && !with_target) continue;
    if (t->empty()) throw ConfigError("the graph takes input '" + name + "', which is not available here");
    in[name] = *t;
  }
  return in;
}

std::string garment_output(const Graph& graph) {
  const auto names = graph.output_names();
  if (names.empty()) throw ConfigError(graph.spec().file + ": the graph has no outputs (the predicted garment)");
  return std::find(names.begin(), names.end(), "garment") != names.end() ? "garment" : names.front();
}

Model::Model(Model&&) noexcept = default;
Model::~Model() = default;

Model Model::load(const Registry& registry, const fs::path& file, const fs::path& cache_dir) {
  return load(registry, file, ParamOverrides{}, cache_dir);
}

Model Model::load(const Registry& registry, const fs::path& file, const ParamOverrides& overrides, const fs::path& cache_dir) {
  Checkpoint checkpoint = read_checkpoint(file);
  refuse_training_state(checkpoint, file, "");
  const auto& meta = checkpoint.meta;
  const auto assets = meta.find("assets");
  if (assets == meta.end())
    throw ConfigError(file.string() + ": not a drape model: /meta has no `assets` (a training state or a plain "
                      "checkpoint? drape train writes the model to --out)");
  // Overrides (node.param=value, node.in.port=ref) go into the graph's text, as drape model set writes them.
  const GraphSpec spec =
      parse_graph_text(overrides.empty() ? checkpoint.graph : graph_with_overrides(checkpoint.graph, overrides, file.string()),
                       file.string() + (overrides.empty() ? " (graph)" : " (graph, with --set)"));
  const auto chart = meta.find("size_chart");
  Model m = build(registry, spec, parse_assets_spec(assets->second, file.string() + ": /meta assets"), 0, cache_dir,
                  chart == meta.end() ? std::string() : chart->second, file.string() + ": /meta size_chart");
  m.file_ = file;
  m.checkpoint_ = std::move(checkpoint);
  const auto& loaded = m.checkpoint_.meta;
  if (auto h = loaded.find("assets_hash"); h != loaded.end()) m.assets_changed_ = h->second != m.assets_->hash;
  load_weights(file, *m.graph_);
  if (const auto output = loaded.find("output"); output != loaded.end()) m.output_ = output->second;
  // Its /meta output names one of the graph's outputs (a damaged or edited
  // file said "failed: no graph output named ...", naming no file).
  const std::vector<std::string> outputs = m.graph_->output_names();
  if (std::find(outputs.begin(), outputs.end(), m.output_) == outputs.end())
    throw ConfigError(file.string() + ": /meta output '" + m.output_ + "' is no output of its graph" +
                      did_you_mean(m.output_, outputs));
  return m;
}

Model Model::untrained(const Registry& registry, const GraphSpec& graph, const AssetsSpec& spec, std::uint64_t seed,
                       const fs::path& cache_dir) {
  Model m = build(registry, graph, spec, seed, cache_dir);
  m.file_ = graph.file + " (untrained)";
  m.checkpoint_.graph = graph.text;
  return m;
}

Model Model::build(const Registry& registry, const GraphSpec& graph, const AssetsSpec& spec, std::uint64_t seed,
                   const fs::path& cache_dir, const std::string& size_chart, const std::string& chart_source) {
  Model m;
  m.assets_spec_ = spec;
  m.assets_ = build_assets(registry, spec, cache_dir);
  m.body_model_ = make_body_model(registry, spec);
  check_graph_inputs(graph);
  GraphOptions options;
  options.dims = graph_dims(*m.assets_, static_cast<int>(m.body_model_->mean_shape().size()));
  options.assets = m.assets_.get();
  options.seed = seed;
  if (!size_chart.empty()) {
    // Each size's pattern is built when a body first wears it (the spec and
    // the names by value: the node may ask after this returns).
    const SizeTable table = SizeTable::parse(size_chart, chart_source);
    std::vector<std::pair<std::string, double>> sizes;
    std::vector<double> grades;
    for (const auto& [name, girth] : table.girth) {
      sizes.emplace_back(name, table.grade(name));
      grades.push_back(sizes.back().second);
    }
    m.garment_sizes_ = std::make_shared<const GarmentSizes>(
        std::move(grades), [&registry, spec, sizes](std::size_t k) {
          return garment_materials(registry, spec, {sizes.at(k)}).front().second;
        });
    options.garment_sizes = m.garment_sizes_;
  }
  m.graph_ = std::make_unique<Graph>(graph, registry, options);
  m.output_ = garment_output(*m.graph_);
  m.set_up_mirror_average(registry, graph);
  return m;
}

// Test-time mirror averaging (docs/poses.md, "The mirror average"): a model
// of posed drapes trained on the drapes and their mirror images is not
// exactly equivariant, and its two answers for a body (its own, and the
// reflection of its answer for the mirrored pose) err apart; their mean is
// closer to the drape (on the human rig's 200 posed test bodies 1.287
// against 1.356 cm) for one more pass of the network's nodes that read the
// pose (the twin shares the rest body, so the encoder runs once). Needs the
// pose space's mirror (mirrored_pose). The twin keeps a symmetric body's rest
// shape and mirrors its pose, as the mirrored training drapes did
// (scripts/mirror_dataset.py); an asymmetric body (a user's) is reflected
// through the mean body's mirror map (mirrored_batch).
void Model::set_up_mirror_average(const Registry& registry, const GraphSpec& graph) {
  mirror_node_.clear();
  post_node_.clear();
  const std::vector<PushOutSetting> posts = push_out_settings(registry, graph);
  garment_mirror_.reset();
  body_mirror_.reset();
  twin_reads_posed_body_ = true;
  for (const PushOutSetting& post : posts) {
    if (!post.mirror_average) continue;
    const std::string what = "node '" + post.node + "' mirror_average: ";
    if (!mirror_node_.empty()) throw ConfigError(what + "the mirror average is already done before node '" + mirror_node_ + "'");
    if (!needs_input("pose") || !needs_input("unposed_body"))
      throw ConfigError(what + "the mirror average needs a model of posed drapes (a graph with the inputs pose and "
                        "unposed_body): an A-pose model's twin would be the same body");
    for (const PoseAngle& angle : body_model_->pose_angles())
      if (angle.mirror == PoseAngle::Mirror::unknown)
        throw ConfigError(what + "the body model '" + assets_spec_.body_model + "' does not say how its angle '" +
                          angle.name + "' mirrors (only drape's human pose space does)");
    if (!assets_->garment) throw ConfigError(what + "no garment is bound");
    std::as_const(*graph_).fed_into(post.node, "x");  // (throws when x is a graph input: nothing to average)
    mirror_node_ = post.node;
    twin_reads_posed_body_ = graph_->input_read_before("body", mirror_node_);
    garment_mirror_ = std::make_shared<const geometry::MirrorMap>(
        geometry::mirror_map(assets_->garment->mesh.vertices, assets_->garment->mesh.faces));
    body_mirror_ = std::make_shared<const geometry::MirrorMap>(geometry::mirror_map(assets_->body.vertices, assets_->body.faces));
  }
  // The push-out the network's drape is fed to, as the model's output; not
  // one with nodes between it and the mirror average (forward_network could
  // not give its input as predict makes it).
  for (const auto& [name, ref] : graph.outputs)
    if (name == output_)
      for (const PushOutSetting& post : posts)
        if (post.node == ref.node && post.enabled && (mirror_node_.empty() || mirror_node_ == post.node))
          post_node_ = post.node;
}

SampleBatch Model::mirrored_batch(const SampleBatch& batch) const {
  if (batch.unposed_body.empty() || batch.pose.empty())
    throw ConfigError("the mirror average needs each body at rest and its pose");
  const auto angles = body_model_->pose_angles();
  if (batch.pose.cols() != static_cast<int>(angles.size()))
    throw ConfigError("the mirror average: the batch's poses have " + std::to_string(batch.pose.cols()) +
                      " angles, the body model " + std::to_string(angles.size()));
  SampleBatch out = batch;
  for (int b = 0; b < batch.size(); ++b) {
    Eigen::MatrixX3d unposed = batch.unposed_body.mat(b).cast<double>();
    if (body_mirror_) {
      // An asymmetric body's twin is its reflection (a symmetric one keeps
      // its bits: the nodes that read only the rest body are then shared).
      Eigen::MatrixX3d reflected = geometry::mirrored(*body_mirror_, unposed);
      if ((reflected - unposed).rowwise().norm().mean() > kAsymmetricBody) unposed = std::move(reflected);
    }
    // The twin's posed body only when the network reads it (a world-space
    // graph): the push-out, which does, runs on the batch's own.
    const SampleBatch twin = posed_body_batch(*body_model_, unposed, mirrored_pose(batch_pose(batch, b, angles), angles),
                                              twin_reads_posed_body_);
    if (twin_reads_posed_body_) out.body.mat(b) = twin.body.mat(0);
    out.unposed_body.mat(b) = twin.unposed_body.mat(0);
    out.joint_transforms.mat(b) = twin.joint_transforms.mat(0);
    out.pose.mat(b) = twin.pose.mat(0);
  }
  return out;
}

namespace {

// Whether the graph has an input of this name (what a batch must then carry).
bool takes(const Graph& graph, const std::string& input) {
  const auto inputs = graph.input_names();
  return std::find(inputs.begin(), inputs.end(), input) != inputs.end();
}

}  // namespace

bool Model::needs_input(const std::string& name) const { return takes(*graph_, name); }

bool reads_pose(const std::vector<std::string>& graph_inputs) {
  return std::any_of(graph_inputs.begin(), graph_inputs.end(), [](const std::string& name) {
    return name == "pose" || name == "unposed_body" || name == "joint_transforms";
  });
}

namespace {

// The flag of each size: the seed's 0 regular, 1 small, then the larger grades,
// then the sizes below small (added after the larger ones, so that the flags of
// datasets made before keep their meaning).
struct SizeFlag {
  const char* name;
  float flag;
};
constexpr SizeFlag kSizeFlags[] = {{"regular", 0.0f}, {"small", 1.0f},   {"large", 2.0f},   {"xlarge", 3.0f},
                                   {"2xlarge", 4.0f}, {"3xlarge", 5.0f}, {"4xlarge", 6.0f}, {"5xlarge", 7.0f},
                                   {"6xlarge", 8.0f}, {"xsmall", 9.0f},  {"2xsmall", 10.0f}, {"3xsmall", 11.0f}};

}  // namespace

float garment_size_flag(const std::string& size) {
  for (const SizeFlag& s : kSizeFlags)
    if (size == s.name) return s.flag;
  throw ConfigError("garment size '" + size + "': the size flag knows " + garment_size_choices());
}

std::string garment_size_choices() {
  std::string text;
  const std::size_t n = std::size(kSizeFlags);
  for (std::size_t i = 0; i < n; ++i)
    text += (i == 0 ? "" : i + 1 == n ? " or " : ", ") + std::string(kSizeFlags[i].name) + " (" +
            std::to_string(static_cast<int>(kSizeFlags[i].flag)) + ")";
  return text;
}

float garment_size_flag(const Scene& scene) {
  const auto size = scene.garment_params.find("size");
  return garment_size_flag(size != scene.garment_params.end() ? size->second.node.as<std::string>() : "regular");
}

namespace {

void require_garment_size(const DatasetLayout& layout) {
  if (!layout.has_stat("garment_size"))
    throw ConfigError("the graph takes garment_size, but the dataset has no garment_size statistic (datasets made "
                      "by drape generate since it records one)");
}

Tensor column(const std::vector<double>& values) {
  Tensor t(static_cast<int>(values.size()), 1, 1);
  for (std::size_t i = 0; i < values.size(); ++i) t(static_cast<int>(i), 0, 0) = static_cast<float>(values[i]);
  return t;
}

}  // namespace

std::vector<double> garment_grades(const DatasetReader& reader, const std::vector<std::size_t>& indices) {
  const DatasetLayout& layout = reader.layout();
  if (layout.has_stat("garment_grade")) return reader.stat("garment_grade", indices);
  // Made before the statistic: every sample wears its scene's garment, which
  // is the design size when the size flag says regular (0) or is absent.
  const bool design_size = !layout.has_stat("garment_size") || [&] {
    for (double f : reader.stat("garment_size", indices))
      if (f != 0.0) return false;
    return true;
  }();
  if (!design_size)
    throw ConfigError("the graph takes garment_grade, but the dataset has no garment_grade statistic and its samples wear "
                      "other sizes than the design size (made before drape generate recorded it): generate it again");
  const Scene scene = parse_scene(layout.scene, reader.name() + " (scene attribute)");
  return std::vector<double>(indices.size(), scene.garment_grade);
}

SampleBatch read_samples(const DatasetReader& reader, const std::vector<std::size_t>& indices, const Graph& graph,
                         bool with_target) {
  SampleBatch b;
  b.body = reader.body_vertices(indices);
  if (with_target) b.target = reader.garment_vertices(indices);
  if (takes(graph, "body_params")) b.body_params = reader.body_params(indices);
  if (takes(graph, "garment_size")) {
    require_garment_size(reader.layout());
    const std::vector<double> size = reader.stat("garment_size", indices);
    b.garment_size = Tensor(static_cast<int>(indices.size()), 1, 1);
    for (std::size_t i = 0; i < size.size(); ++i) b.garment_size(static_cast<int>(i), 0, 0) = static_cast<float>(size[i]);
  }
  if (takes(graph, "garment_grade")) b.garment_grade = column(garment_grades(reader, indices));
  if (takes(graph, "unposed_body") || takes(graph, "joint_transforms") || takes(graph, "pose")) {
    DatasetReader::Posing posing = reader.posing(indices);
    b.unposed_body = std::move(posing.unposed);
    b.joint_transforms = std::move(posing.transforms);
    b.pose = std::move(posing.angles);
  }
  return b;
}

SampleBatch sample_batch(const DatasetSample& sample, const DatasetLayout& layout, const Graph& graph,
                         const BodyModel* body_model) {
  SampleBatch b;
  b.body = Tensor(1, static_cast<int>(sample.body_vertices.rows()), 3);
  b.body.mat(0) = sample.body_vertices;
  if (takes(graph, "body_params")) {
    b.body_params = Tensor(1, 1, static_cast<int>(sample.body_params.size()));
    b.body_params.mat(0).row(0) = sample.body_params.transpose();
  }
  if (takes(graph, "garment_size")) {
    require_garment_size(layout);
    b.garment_size = Tensor(1, 1, 1);
    b.garment_size(0, 0, 0) = static_cast<float>(sample.stats.at("garment_size"));
  }
  if (takes(graph, "garment_grade")) {
    // Made before the statistic: the scene's grade when the sample wears the
    // design size, as garment_grades reads a dataset (optimize --data
    // refused the shipped friction shards that eval reads, an outside check).
    const auto grade = sample.stats.find("garment_grade");
    if (grade != sample.stats.end()) {
      b.garment_grade = column({grade->second});
    } else {
      const auto size = sample.stats.find("garment_size");
      if (size != sample.stats.end() && size->second != 0.0)
        throw ConfigError("the graph takes garment_grade, but the sample has no garment_grade statistic and wears another "
                          "size than the design size (made before drape generate recorded it): generate it again");
      b.garment_grade = column({parse_scene(layout.scene, "the dataset's stored scene").garment_grade});
    }
  }
  if (takes(graph, "unposed_body") || takes(graph, "joint_transforms") || takes(graph, "pose")) {
    if (!body_model) throw Error("sample_batch: a graph that takes a pose needs the dataset's body model");
    Pose pose;
    for (std::size_t a = 0; a < layout.pose_angles.size(); ++a)
      pose.angles[layout.pose_angles[a]] = static_cast<double>(sample.pose[static_cast<Eigen::Index>(a)]);
    const SampleBatch posed =
        posed_body_batch(*body_model, body_model->vertices(sample.body_params.cast<double>()), pose, false);
    b.unposed_body = posed.unposed_body;
    b.joint_transforms = posed.joint_transforms;
    b.pose = posed.pose;  // b.body stays the stored one: the body the drape was simulated on
  }
  return b;
}

Pose batch_pose(const SampleBatch& batch, int i, const std::vector<PoseAngle>& angles) {
  Pose pose;
  for (std::size_t a = 0; a < angles.size(); ++a) {
    double degrees = static_cast<double>(batch.pose(i, 0, static_cast<int>(a))) * 180.0 / M_PI;
    // An angle at the end of its range comes back from float radians a few
    // millionths of a degree past it (-90 as -90.0000034), which the range
    // check would refuse: such a rounding is put back; anything further is not.
    constexpr double kRounding = 1e-3;
    if (degrees < angles[a].min && degrees > angles[a].min - kRounding) degrees = angles[a].min;
    if (degrees > angles[a].max && degrees < angles[a].max + kRounding) degrees = angles[a].max;
    pose.angles[angles[a].name] = degrees;
  }
  return pose;
}

SampleBatch posed_body_batch(const BodyModel& model, const Eigen::MatrixX3d& unposed, const Pose& pose,
                             bool with_posed_body) {
  if (!model.poseable()) throw ConfigError("this body model has no skeleton: it takes no pose");
  const Pose full = full_pose(model, pose, unposed);
  SampleBatch b;
  const auto to_tensor = [](const Eigen::MatrixXd& m) {
    Tensor t(1, static_cast<int>(m.rows()), static_cast<int>(m.cols()));
    t.mat(0) = m.cast<float>();
    return t;
  };
  if (with_posed_body) b.body = to_tensor(model.posed_vertices(unposed, full, 1.0));
  b.unposed_body = to_tensor(unposed);
  const MatrixRM transforms = transforms_rows(model.joint_transforms(unposed, full));
  b.joint_transforms = Tensor(1, static_cast<int>(transforms.rows()), 12);
  b.joint_transforms.mat(0) = transforms;
  const auto angles = model.pose_angles();
  b.pose = Tensor(1, 1, static_cast<int>(angles.size()));
  for (std::size_t a = 0; a < angles.size(); ++a)
    b.pose(0, 0, static_cast<int>(a)) = static_cast<float>(full.angles.at(angles[a].name) * M_PI / 180.0);
  return b;
}

bool Model::needs_body_params() const { return needs_input("body_params"); }

Tensor Model::predict(const SampleBatch& batch) {
  if (batch.size() <= 0) throw Error("predict: no bodies");
  require_vertex_count(batch.body.rows(), assets_->body.num_vertices(), "the body",
                       "the model's body model '" + assets_spec_.body_model + "'");
  if (mirror_node_.empty()) return forward(graph_inputs(*graph_, batch, false), nullptr);
  const auto twin = graph_inputs(*graph_, mirrored_batch(batch), false);
  return forward(graph_inputs(*graph_, batch, false), &twin);
}

const Tensor& Model::forward(const std::map<std::string, Tensor>& inputs, const std::map<std::string, Tensor>* twin_inputs) {
  if (mirror_node_.empty()) {
    graph_->forward(inputs, false);
    return graph_->output(output_);
  }
  mirror_mean(inputs, twin_inputs);
  graph_->forward_from(mirror_node_);
  return graph_->output(output_);
}

Tensor& Model::mirror_mean(const std::map<std::string, Tensor>& inputs, const std::map<std::string, Tensor>* twin_inputs) {
  if (!twin_inputs) throw Error("Model::forward: the mirror average needs the twin's inputs");
  // The twin first, so that what the push-out then reads (the body, the
  // grade) is the batch's own.
  graph_->forward_until(*twin_inputs, mirror_node_);
  const Tensor twin = std::as_const(*graph_).fed_into(mirror_node_, "x");
  // The nodes that read only what the two share (the rest body: the
  // encoder) keep the twin's outputs.
  graph_->forward_until(inputs, mirror_node_, true);
  Tensor& garment = graph_->fed_into(mirror_node_, "x");
  for (int b = 0; b < garment.batch(); ++b) {
    const Eigen::MatrixX3d reflected = geometry::mirrored(*garment_mirror_, twin.mat(b).cast<double>());
    garment.mat(b) = (0.5 * (garment.mat(b).cast<double>() + reflected)).cast<float>();
  }
  return garment;
}

const Tensor& Model::forward_network(const std::map<std::string, Tensor>& inputs,
                                     const std::map<std::string, Tensor>* twin_inputs) {
  if (post_node_.empty()) return forward(inputs, twin_inputs);
  if (!mirror_node_.empty()) return mirror_mean(inputs, twin_inputs);  // (fed to post_node_, which is the mirror node)
  graph_->forward_until(inputs, post_node_);
  return std::as_const(*graph_).fed_into(post_node_, "x");
}

void Model::backward(const Tensor& grad, const std::map<std::string, Tensor>* twin_inputs) {
  backward_pass(grad, twin_inputs, false);
}

void Model::backward_network(const Tensor& grad, const std::map<std::string, Tensor>* twin_inputs) {
  backward_pass(grad, twin_inputs, !post_node_.empty());
}

void Model::backward_pass(const Tensor& grad, const std::map<std::string, Tensor>* twin_inputs, bool from_post_input) {
  const auto from = [&](const Tensor& g) {
    if (from_post_input) graph_->backward_from_fed(post_node_, "x", g);
    else graph_->backward_from_output(output_, g);
  };
  if (mirror_node_.empty()) {
    from(grad);
    return;
  }
  if (!twin_inputs) throw Error("Model::backward: the mirror average needs the twin's inputs");
  Tensor half = grad;
  half.vec() *= 0.5f;
  from(half);
  // The twin's pass again (the graph holds the batch's), then its share: the
  // push-out is not run for it, and its backward only passes the gradient on.
  graph_->forward_until(*twin_inputs, mirror_node_, true);
  for (int b = 0; b < grad.batch(); ++b)
    half.mat(b) = (0.5 * geometry::mirrored_adjoint(*garment_mirror_, grad.mat(b).cast<double>(), grad.rows())).cast<float>();
  from(half);
}

SampleBatch Model::body_for(const BodyRequest& request) const { return body_batch(*body_model_, request); }

std::unique_ptr<BodyModel> make_body_model(const Registry& registry, const AssetsSpec& spec) {
  const PluginDescriptor& d = registry.get(spec.body_model);
  return registry.create_body(spec.body_model, Params(d.params, param_values(spec.body_params, "assets body"),
                                                      "body '" + spec.body_model + "'"));
}

SampleBatch body_batch(const BodyModel& model, const BodyRequest& request, int copies) {
  const Eigen::VectorXd shape = model.solve(request);
  const Eigen::MatrixX3d v = model.vertices(shape);
  SampleBatch b;
  b.body = Tensor(copies, static_cast<int>(v.rows()), 3);
  b.body_params = Tensor(copies, 1, static_cast<int>(shape.size()));
  for (int c = 0; c < copies; ++c) {
    b.body.mat(c) = v.cast<float>();
    for (Eigen::Index i = 0; i < shape.size(); ++i) b.body_params(c, 0, static_cast<int>(i)) = static_cast<float>(shape[i]);
  }
  return b;
}

}  // namespace drape
