#pragma once
// A trained model (`drape train` writes it, `drape predict`, `drape eval` and
// `drape bench infer` read it; layout in docs/formats.md): a checkpoint whose
// root attribute `graph` is the resolved graph, whose /weights are the best
// weights, whose /meta names the template assets (meta `assets`, the
// AssetsSpec as YAML) so that the same assets are rebuilt, and whose /history
// holds the per-epoch losses.
//
// Graph inputs are fed by name, the same way in training and at inference:
//   body         [body_vertices, 3]   body vertices (metres, the body model's topology)
//   body_params  [1, body_params]     the body model's shape parameters
//   target       [garment_vertices, 3] the ground-truth garment (losses only)
//   garment_size, garment_grade [1, 1] the size the sample wears (docs/garments.md)
//   unposed_body [body_vertices, 3]   the body in its rest pose (docs/poses.md)
//   joint_transforms [joints, 12]     each joint's transform from the rest pose into the sample's (R row by row, t)
//   pose         [1, pose_angles]     the joint angles in radians, the body model's pose_angles order
// A graph input of any other name is refused when the graph is loaded. The
// predicted garment is the output named `garment`, else the graph's first output.
#include <drape/assets/assets.hpp>
#include <drape/bodies/body.hpp>
#include <drape/geometry/mirror_map.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/graph.hpp>
#include <drape/scene/scene.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace drape {

// The inverse of AssetsSpec::yaml(). ConfigError naming `what` for anything else.
AssetsSpec parse_assets_spec(const std::string& yaml, const std::string& what);

// The assets of the template a scene (a dataset's `scene` attribute) drapes:
// its body model and garment with their parameters.
AssetsSpec assets_spec_for(const Scene& scene, int eigen_k, int levels = 4);

// Samples as graph-ready tensors; empty tensors are "not available".
struct SampleBatch {
  Tensor body;         // [n, Nb, 3]
  Tensor body_params;  // [n, 1, P]
  Tensor target;       // [n, Ng, 3]
  // [n, 1, 1]: which garment size each sample wears, the dataset statistic
  // garment_size (0 regular, 1 small), for graphs trained on several sizes.
  Tensor garment_size;
  // [n, 1, 1]: the grade of the garment each sample wears (the dataset
  // statistic garment_grade: its size's girth over the design size's), for
  // graphs trained on drapes in each body's own size.
  Tensor garment_grade;
  // Posing (docs/poses.md; DatasetReader::Posing): the body at rest
  // [n, Nb, 3], the joints' transforms into the pose [n, J, 12], the angles
  // in radians [n, 1, A]. `body` is the posed body.
  Tensor unposed_body;
  Tensor joint_transforms;
  Tensor pose;
  int size() const { return body.batch(); }
  // Samples first .. first+count-1 of every tensor that is present.
  SampleBatch slice(int first, int count) const;
};

// The body plugin an assets spec names, with its parameters.
std::unique_ptr<BodyModel> make_body_model(const Registry& registry, const AssetsSpec& spec);
// A body of `model` for a request (ConfigError when the model cannot reach
// it), as `copies` identical samples: vertices and parameters.
SampleBatch body_batch(const BodyModel& model, const BodyRequest& request, int copies = 1);
// One body of `model` given by its unposed mesh in `pose` (angles it does not
// set at the body's rest angles): body (posed), unposed_body,
// joint_transforms and pose, as a dataset sample of that body would have them.
// Without with_posed_body, `body` is left empty (posing the vertices is most
// of the cost, and a caller that keeps another body need not pay it).
// ConfigError when the model has no skeleton.
SampleBatch posed_body_batch(const BodyModel& model, const Eigen::MatrixX3d& unposed, const Pose& pose,
                             bool with_posed_body = true);
// Sample i's pose in a batch (its `pose` tensor, radians, in the order of
// `angles`) as degrees by name.
Pose batch_pose(const SampleBatch& batch, int i, const std::vector<PoseAngle>& angles);

// Known graph inputs and their sizes (`dims` for GraphOptions): the assets'
// sizes plus body_params.
std::map<std::string, int> graph_dims(const Assets& assets, int body_params);
// ConfigError (naming the graph file) when the graph has an input other than
// body, body_params and target.
void check_graph_inputs(const GraphSpec& spec);
// The batch's tensors under the names of the graph's inputs; `target` only
// when with_target (a forward pass without losses does not need it). A
// declared input the batch does not hold is a ConfigError.
std::map<std::string, Tensor> graph_inputs(const Graph& graph, const SampleBatch& batch, bool with_target);
// The output that holds the predicted garment.
std::string garment_output(const Graph& graph);

// A batch of dataset samples with what `graph` takes: body, body_params and
// garment_size when it has those inputs, the target when with_target.
class DatasetReader;
struct DatasetLayout;
struct DatasetSample;
SampleBatch read_samples(const DatasetReader& reader, const std::vector<std::size_t>& indices, const Graph& graph,
                         bool with_target);
// The same for one sample already read (DatasetReader::sample), without the
// target. A graph that takes the posing inputs needs `body_model` (the
// dataset's): the sample's body at rest is rebuilt from its shape parameters
// and posed in its stored angles (at rest in an A-pose dataset).
SampleBatch sample_batch(const DatasetSample& sample, const DatasetLayout& layout, const Graph& graph,
                         const BodyModel* body_model = nullptr);

// The garment_size input of a size name: 0 regular, 1 small (the seed's flag),
// then 2 large, 3 xlarge; ConfigError for another name.
float garment_size_flag(const std::string& size);
// The same for the garment a scene names (its `size` parameter; regular when absent).
float garment_size_flag(const Scene& scene);
// "regular (0), small (1), large (2) or xlarge (3)": the sizes the flag knows, for messages.
std::string garment_size_choices();
// The garment_grade of dataset samples: the statistic, or for a dataset made
// before drape recorded it whose samples all wear the design size, the
// stored scene's grade. ConfigError otherwise.
std::vector<double> garment_grades(const DatasetReader& reader, const std::vector<std::size_t>& indices);

// Whether a graph with these inputs drapes posed bodies: any of the inputs
// that carry a pose (pose, unposed_body, joint_transforms). What
// model_takes_pose, train's warning and `model info` ask of a graph.
bool reads_pose(const std::vector<std::string>& graph_inputs);

class Model {
 public:
  // Reads the model file, rebuilds the assets (from `cache_dir`, see
  // build_assets) and the graph, and loads the weights. ConfigError for a file
  // that is not a drape model or does not fit its graph.
  static Model load(const Registry& registry, const std::filesystem::path& file,
                    const std::filesystem::path& cache_dir = default_cache_dir());
  // The same with some node parameters changed before the graph is built (node
  // name -> parameter -> YAML value), for knobs that leave the weights' shapes
  // alone, e.g. {"spectral", {{"use_k", "64"}}}. ConfigError for an unknown node.
  using ParamOverrides = std::map<std::string, std::map<std::string, std::string>>;
  static Model load(const Registry& registry, const std::filesystem::path& file, const ParamOverrides& overrides,
                    const std::filesystem::path& cache_dir = default_cache_dir());

  // A model with freshly initialised weights (seed) of a graph on the assets
  // of a spec -- what benchmarks time when the cost does not depend on the weights.
  static Model untrained(const Registry& registry, const GraphSpec& graph, const AssetsSpec& spec, std::uint64_t seed = 0,
                         const std::filesystem::path& cache_dir = default_cache_dir());

  Model(Model&&) noexcept;
  ~Model();

  const std::filesystem::path& file() const { return file_; }
  const Checkpoint& checkpoint() const { return checkpoint_; }  // graph text, meta, history
  const AssetsSpec& assets_spec() const { return assets_spec_; }
  const Assets& assets() const { return *assets_; }
  std::shared_ptr<const Assets> shared_assets() const { return assets_; }
  // The garment in each size of the model's size chart, each built at its
  // first use (garment_sizes.hpp: what the push-out's strain limit holds a
  // body's size to); null for a model without a chart.
  const std::shared_ptr<const GarmentSizes>& garment_sizes() const { return garment_sizes_; }
  const BodyModel& body_model() const { return *body_model_; }
  Graph& graph() { return *graph_; }
  const Graph& graph() const { return *graph_; }
  const std::string& output() const { return output_; }
  bool needs_body_params() const;
  bool needs_input(const std::string& name) const;
  // True when the rebuilt assets differ from the ones the model was trained
  // with (meta `assets_hash`), e.g. after a change of the garment plugin.
  bool assets_changed() const { return assets_changed_; }

  // Garments [n, Ng, 3] for the batch's bodies (and body_params when the graph uses them).
  // With the mirror average (a push_out node's `mirror_average`), the network
  // also drapes each body in its mirrored pose, and the garment before the
  // push-out is the mean of its own and that twin's reflection.
  Tensor predict(const SampleBatch& batch);
  // The push_out node the mirror average runs before; empty when it is off.
  const std::string& mirror_average_node() const { return mirror_node_; }
  // The garment template's mirror map (null when the mirror average is off).
  const geometry::MirrorMap* garment_mirror() const { return garment_mirror_.get(); }
  // One pass of the graph on graph inputs as predict runs it: with the mirror
  // average, the twin's inputs (graph_inputs of mirrored_batch) first, the
  // nodes before the push-out only; then the batch's, the mean, the rest.
  // The garment output; the graph holds the batch's own activations.
  const Tensor& forward(const std::map<std::string, Tensor>& inputs, const std::map<std::string, Tensor>* twin);
  // After forward(inputs, twin): `grad`, a gradient of the garment output,
  // into the weights' gradients (added to them; zero_grad first). With the
  // mirror average half goes back through each pass, the twin's reflected
  // back by the map's adjoint (geometry::mirrored_adjoint), its pass run
  // again for its activations: twice the cost of one backward. The push-out
  // passes the gradient straight through.
  void backward(const Tensor& grad, const std::map<std::string, Tensor>* twin);
  // As forward, but the garment the push-out is fed (the network's own
  // drape: with the mirror average, the mean), the push-out not run; forward
  // itself when there is no push_out node (push_out_node()). backward() takes its
  // gradient as it is (the push-out passes it straight through). What the
  // physics optimisation moves: the push-out is not learnt, and a gradient
  // taken where it moved vertices, passed to the weights as if they had
  // moved them, is not the potential's (docs/optimization.md).
  const Tensor& forward_network(const std::map<std::string, Tensor>& inputs, const std::map<std::string, Tensor>* twin);
  // After forward_network: `grad`, a gradient of that drape, into the weights' gradients.
  void backward_network(const Tensor& grad, const std::map<std::string, Tensor>* twin);
  // The push_out node (enabled) whose output is the model's; empty when none.
  const std::string& push_out_node() const { return post_node_; }
  // The batch's bodies at rest in their mirrored poses (mirrored_pose): what
  // the mirror average feeds the network. The joints' transforms and the
  // angles are the mirrored pose's; the posed body is too when the network
  // reads it before the push-out (else it stays the batch's, which the
  // push-out reads). A body symmetric at rest keeps its rest shape (every
  // body of the body models: the mirrored training drapes did the same); an
  // asymmetric one (its reflection through the mean body's mirror map lies
  // more than kAsymmetricBody from it on average) is reflected.
  SampleBatch mirrored_batch(const SampleBatch& batch) const;
  // The mean distance (m) between a body's reflection and the body above
  // which its twin is its reflection: 10 times the largest of 40 bodies of
  // the human rig's space (BMI 10.5-64, both sexes, 1.5-2.0 m: 0.046 mm);
  // one arm 10 % thicker is 11 mm.
  static constexpr double kAsymmetricBody = 0.5e-3;
  // A body of the model's body plugin for a request: vertices and parameters.
  SampleBatch body_for(const BodyRequest& request) const;

 private:
  Model() = default;
  // The assets, body model and graph (fresh weights) shared by load and untrained.
  // size_chart: the model's (meta size_chart), whose sizes' garments the
  // nodes may ask for (NodeContext::garment_sizes); empty: none. chart_source
  // names it in the error when it is not a size chart (a damaged file).
  static Model build(const Registry& registry, const GraphSpec& graph, const AssetsSpec& spec, std::uint64_t seed,
                     const std::filesystem::path& cache_dir, const std::string& size_chart = "",
                     const std::string& chart_source = "the model's size_chart");
  std::filesystem::path file_;
  Checkpoint checkpoint_;
  AssetsSpec assets_spec_;
  std::shared_ptr<const Assets> assets_;
  std::unique_ptr<BodyModel> body_model_;
  std::unique_ptr<Graph> graph_;
  std::shared_ptr<const GarmentSizes> garment_sizes_;  // of the size chart; null without one
  // The mirror average: the push_out node it runs before, and the garment
  // template's mirror map (empty name: off).
  std::string mirror_node_;
  // The push_out node (enabled) whose output is the model's output, and, with
  // the mirror average, the mirror node itself (empty: none).
  std::string post_node_;
  // With the mirror average: the graph run to the mirror node for the twin
  // and then the batch, and the garment it is fed made their mean (returned).
  Tensor& mirror_mean(const std::map<std::string, Tensor>& inputs, const std::map<std::string, Tensor>* twin_inputs);
  // backward and backward_network: from the output, or from what the push-out is fed.
  void backward_pass(const Tensor& grad, const std::map<std::string, Tensor>* twin_inputs, bool from_post_input);
  std::shared_ptr<const geometry::MirrorMap> garment_mirror_;
  std::shared_ptr<const geometry::MirrorMap> body_mirror_;  // of the mean body: a user's asymmetric body reflected
  bool twin_reads_posed_body_ = true;  // a node before the mirror node reads `body` (else the twin's is not posed)
  void set_up_mirror_average(const Registry& registry, const GraphSpec& graph);
  std::string output_;
  bool assets_changed_ = false;
};

// The pretrained model shipped with drape (models/tshirt-coarse-human.h5 of
// the source tree, trained by scripts/train_human_model.sh), which `drape predict`
// uses when no --model is given. Looked up in order: $DRAPE_MODEL; then
// models/<kDefaultModelFile> in the shipped files' folders (shipped_data_dirs():
// $DRAPE_DATA_DIR, <prefix>/share/drape next to an installed framework
// library, the source tree this build came from), never the current folder.
// Empty when none of them has it.
std::filesystem::path default_model_path();

// The default: the coarse T-shirt in each body's size on the parametric
// body's human rig (docs/bodies.md, "The human rig, the default"). The
// mannequin's model of the same shirt stays as models/tshirt-coarse.h5.
inline constexpr const char* kDefaultModelFile = "tshirt-coarse-human.h5";

// models/<file_name> among the shipped files' folders, as default_model_path
// looks (without $DRAPE_MODEL); empty when none has it.
std::filesystem::path shipped_model_path(const std::string& file_name);

}  // namespace drape
