#pragma once
// Data-flow graphs read from YAML. A graph names its inputs, nodes (type, params,
// inputs by `node` or `node.port`), outputs and weighted losses. A file may name a
// `base:` graph and override a few nodes or loss weights (an ablation). The whole
// graph is validated before anything runs; errors name the file, line and node.
//
//   inputs:  { body: [body_vertices, 3], target: [garment_vertices, 3] }
//   nodes:
//     encoder: { type: cnn1d, in: body, params: { channels: [32, 64] } }
//     decoder: { type: mlp,   in: encoder.features }
//   outputs: { garment: decoder }
//   losses:
//     l2: 1.0                                  # type l2, inputs bound by port name
//     edge: { type: edge, weight: 0.5, in: { pred: garment, target: target } }
//
// Loss ports not wired explicitly bind by name: `pred` to the first output, any
// other port to the graph input of that name.
#include <drape/node.hpp>
#include <drape/registry.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drape {

struct GraphOptions {
  std::map<std::string, int> dims;  // symbolic sizes used in `inputs:` (e.g. body_vertices)
  const Assets* assets = nullptr;
  std::uint64_t seed = 0;           // weight initialisation
  // Handed to every node's setup (NodeContext::garment_sizes).
  std::shared_ptr<const GarmentSizes> garment_sizes = {};
  // For tests: fill every reused gradient buffer with NaN before backward, so
  // that a node which reads a grad_in before writing it (the graph no longer
  // zeroes them) turns the weights' gradients into NaN instead of passing.
  bool poison_gradient_buffers = false;
};

struct PortRef {
  std::string node;  // a node, a graph input, or an output name (for losses)
  std::string port;  // empty: the node's only/first output
  SourceLocation where;
  std::string str() const { return port.empty() ? node : node + "." + port; }
};

// One node as written (after base merging), before it is built.
struct NodeSpec {
  std::string name;
  std::string type;
  std::vector<std::pair<std::string, PortRef>> inputs;  // (port or "" for positional, ref)
  ParamValues params;
  SourceLocation where;
  bool is_loss = false;
  double weight = 1.0;  // losses only
};

struct GraphSpec {
  std::string file;  // the file that was loaded (the ablation, not its base)
  std::vector<std::pair<std::string, std::pair<std::vector<std::string>, SourceLocation>>> inputs;
  std::vector<NodeSpec> nodes;   // in file order; losses included (is_loss)
  std::vector<std::pair<std::string, PortRef>> outputs;
  std::string text;              // the resolved graph as YAML (stored in checkpoints)
};

// Parses a graph file, following `base:` chains. Throws ConfigError with file:line.
GraphSpec parse_graph_file(const std::filesystem::path& file);
GraphSpec parse_graph_text(const std::string& yaml, const std::string& name_for_errors);

class Graph {
 public:
  // Builds and validates every node (types, ports, shapes, cycles).
  Graph(const GraphSpec& spec, const Registry& registry, const GraphOptions& options = {});
  ~Graph();
  Graph(Graph&&) noexcept;

  struct NodeInfo {
    std::string name, type, kind;
    std::vector<std::string> inputs;                  // "port <- ref [r, c]"
    std::vector<std::pair<std::string, Shape>> outputs;
    std::size_t weight_count = 0;
    bool is_loss = false;
    double weight = 0.0;
  };
  std::vector<NodeInfo> describe() const;  // in execution order
  const GraphSpec& spec() const { return spec_; }

  // Runs the nodes needed for the outputs (and the losses when with_losses).
  // Every graph input the run needs must be given, all with one batch size.
  void forward(const std::map<std::string, Tensor>& inputs, bool with_losses = true);
  // Forward in two parts, for a caller that changes what one node is fed
  // between them (Model::predict's mirror average: the network's garment
  // averaged with its mirror twin before the push-out). forward_until runs
  // what forward (without losses) runs but `node` and every node fed by it;
  // fed_into is the tensor one of its ports reads (another node's output,
  // which the caller may change in place: a graph input is refused);
  // forward_from then runs `node` and the nodes fed by it on what is there.
  // With reuse_unchanged, a node whose upstream graph inputs hold the same
  // values as at the last forward keeps its outputs from then instead of
  // running again (the twin and the body share the rest body: the encoder
  // runs once). Only for consecutive passes with the same weights.
  void forward_until(const std::map<std::string, Tensor>& inputs, const std::string& node, bool reuse_unchanged = false);
  // (The mutable one marks the tensor changed: its node runs again at the
  // next forward_until even with reuse_unchanged; the const one only reads.)
  Tensor& fed_into(const std::string& node, const std::string& port);
  const Tensor& fed_into(const std::string& node, const std::string& port) const;
  void forward_from(const std::string& node);
  // Whether a node forward_until(..., node) runs reads the graph input.
  bool input_read_before(const std::string& input, const std::string& node) const;
  // The weighted sum of the batch-mean losses of the last forward.
  double loss() const;
  std::map<std::string, double> loss_terms() const;  // unweighted batch means
  // Reverse mode from the weighted loss; accumulates into every weight's grad.
  void backward();
  // Reverse mode from a given gradient of an output (no losses involved).
  void backward_from_output(const std::string& output, const Tensor& grad);
  // Reverse mode from a given gradient of what `node` reads at `port` (after
  // forward_until(..., node): `node` need not have run).
  void backward_from_fed(const std::string& node, const std::string& port, const Tensor& grad);

  const Tensor& output(const std::string& name) const;
  std::vector<std::string> output_names() const;
  std::vector<std::string> input_names() const;
  Shape input_shape(const std::string& name) const;

  // All learnable weights as "node/weight" -> Weight.
  std::vector<std::pair<std::string, Weight*>> weights();
  void zero_grad();
  double flops_per_sample() const;  // the nodes needed for the outputs

  // Where the last forward spent its time, node by node in execution order
  // (the nodes that ran), with each node's multiply-adds per sample.
  struct NodeTime {
    std::string name, type;
    double ms = 0.0;
    double flops_per_sample = 0.0;
    double backward_ms = 0.0;  // of the last backward (0 when it did not run the node)
    bool is_loss = false;
  };
  std::vector<NodeTime> last_forward_times() const;
  // The same with the last backward's time per node: the nodes that ran in either.
  std::vector<NodeTime> last_step_times() const;

  // Which input ports of a node backward fills (Caffe's propagate_down): those
  // fed by a node that has weights upstream. Graph inputs and constants get no
  // gradient, so a node is never asked for one (`grad_in` lacks those ports).
  std::vector<std::string> gradient_ports(const std::string& node) const;

  struct Impl;  // opaque

 private:
  GraphSpec spec_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace drape
