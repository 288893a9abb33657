// Building, validating and running graphs.
#include <drape/error_context.hpp>
#include <drape/energy.hpp>
#include <drape/fnv1a.hpp>
#include <drape/graph.hpp>

#include "graph_rewrite.hpp"

#include <chrono>
#include <limits>

#include <algorithm>
#include <new>
#include <cstring>
#include <functional>

namespace drape {
namespace {

// A value flowing along an edge: a node's output port or a graph input.
struct Source {
  int node = -1;   // index into Impl::nodes, or -1
  int port = 0;
  int input = -1;  // index into Impl::inputs, or -1
};

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& e : v) s += (s.empty() ? "" : ", ") + e;
  return s.empty() ? "(none)" : s;
}

}  // namespace

struct Graph::Impl {
  struct Built {
    NodeSpec spec;
    const PluginDescriptor* desc = nullptr;
    std::unique_ptr<Node> node;
    std::vector<std::string> in_ports;  // connected input ports
    std::vector<Source> sources;        // parallel to in_ports
    std::vector<std::string> out_ports;
    std::vector<Shape> out_shapes;
    std::vector<Tensor> outputs, out_grads;
    // Per output: its gradient buffer holds a value (a consumer wrote it, or
    // the loss seed). Buffers are reused across steps without being zeroed:
    // the first consumer overwrites one, later ones add to it, and one nobody
    // wrote is zeroed just before the node's backward reads it.
    std::vector<bool> grad_written;
    // A gradient reached one of its outputs: its backward runs.
    bool has_grad() const { return std::find(grad_written.begin(), grad_written.end(), true) != grad_written.end(); }
    bool requires_grad = false;  // has weights upstream (or itself)
    bool for_outputs = false;    // needed to compute the graph outputs
    bool for_losses = false;     // needed to compute the losses
    double forward_ms = 0.0;     // wall time of the last forward (0 when it did not run)
    double backward_ms = 0.0;    // wall time of the last backward (0 when it did not run)
    bool changed_in_place = false;  // fed_into handed out an output since the node last ran
    std::string label() const { return "node '" + spec.name + "' (" + spec.type + ")"; }
  };
  struct Input {
    std::string name;
    Shape shape;
    SourceLocation where;
    Tensor value;
  };
  std::vector<Built> nodes;  // topological order once built
  std::vector<Input> inputs;
  std::vector<std::pair<std::string, Source>> outputs;
  int batch = 0;
  bool ran_losses = false;
  bool poison_gradient_buffers = false;  // GraphOptions::poison_gradient_buffers

  Shape shape_of(const Source& s) const {
    return s.node >= 0 ? nodes[s.node].out_shapes[s.port] : inputs[s.input].shape;
  }
  const Tensor& value_of(const Source& s) const {
    return s.node >= 0 ? nodes[s.node].outputs[s.port] : inputs[s.input].value;
  }

  // Building, in this order.
  void build(const GraphSpec& spec, const Registry& registry, const GraphOptions& options);
  void add_inputs(const GraphSpec& spec, const GraphOptions& options);
  void build_nodes(const GraphSpec& spec, const Registry& registry);
  void wire_inputs(const GraphSpec& spec);
  void sort_topologically();
  void set_up_shapes(const GraphOptions& options);
  void mark_needed_nodes();

  // Running: the graph inputs checked and taken, then the nodes `runs` picks
  // (by index, in topological order); fed_by(n): n and the nodes downstream of it.
  // compare: each input's value against the last one's (changed[i]: it differs, or was not compared).
  std::vector<bool> set_inputs(const std::map<std::string, Tensor>& inputs, bool with_losses, bool compare);
  void run(const std::function<bool(int)>& runs);
  std::vector<bool> fed_by(int node) const;
  const Source& feeding(const std::string& node, const std::string& port) const;  // a node's, never a graph input

  int node_index(const std::string& name) const;
  int existing_node(const std::string& name) const;  // node_index, Error when there is none
  int input_index(const std::string& name) const;
  std::vector<std::string> all_names() const;
  Source resolve(const GraphSpec& spec, const PortRef& r, const std::string& who, int depth) const;
  void wire_node(const GraphSpec& spec, Built& b) const;
};

Graph::~Graph() = default;
Graph::Graph(Graph&&) noexcept = default;

Graph::Graph(const GraphSpec& spec, const Registry& registry, const GraphOptions& options)
    : spec_(spec), impl_(std::make_unique<Impl>()) {
  // The graph runs rewritten where that is cheaper (graph_rewrite.hpp). A
  // graph with a mistake is built again as written, so that the error names
  // its nodes as the user wrote them.
  if (const auto rewritten = detail::gather_before_repeated_concat(spec)) {
    try {
      impl_->build(*rewritten, registry, options);
      return;
    } catch (const ConfigError&) {
      impl_ = std::make_unique<Impl>();
    }
  }
  impl_->build(spec, registry, options);
}

void Graph::Impl::build(const GraphSpec& spec, const Registry& registry, const GraphOptions& options) {
  poison_gradient_buffers = options.poison_gradient_buffers;
  add_inputs(spec, options);
  build_nodes(spec, registry);
  wire_inputs(spec);
  sort_topologically();
  set_up_shapes(options);
  mark_needed_nodes();
}

// Graph inputs and their shapes (symbolic dimensions come from options.dims).
void Graph::Impl::add_inputs(const GraphSpec& spec, const GraphOptions& options) {
  for (const auto& [name, dims] : spec.inputs) {
    int size[2];
    for (int i = 0; i < 2; ++i) {
      const std::string& d = dims.first[i];
      try {
        std::size_t used = 0;
        size[i] = std::stoi(d, &used);
        if (used != d.size()) throw std::invalid_argument(d);
      } catch (const std::exception&) {
        auto it = options.dims.find(d);
        // A number too large for a size was "unknown size '99999999999'".
        if (it == options.dims.end() && !d.empty() &&
            d.find_first_not_of("0123456789") == std::string::npos)
          throw ConfigError(dims.second, "input '" + name + "': size " + d + " is too large (at most " +
                                             std::to_string(std::numeric_limits<int>::max()) + ")");
        if (it == options.dims.end()) {
          std::vector<std::string> known;
          for (const auto& [k, v] : options.dims) known.push_back(k);
          throw ConfigError(dims.second, "input '" + name + "': unknown size '" + d + "'" + did_you_mean(d, known) +
                                             " (known sizes: " + join(known) + ")");
        }
        size[i] = it->second;
      }
      if (size[i] <= 0) throw ConfigError(dims.second, "input '" + name + "': sizes must be positive");
    }
    inputs.push_back({name, {size[0], size[1]}, dims.second, {}});
  }
}

// Build every node: type lookup and parameter validation.
void Graph::Impl::build_nodes(const GraphSpec& spec, const Registry& registry) {
  for (const auto& ns : spec.nodes) {
    if (ns.is_loss && ns.weight == 0.0) continue;  // a disabled loss is not built
    Built b;
    b.spec = ns;
    const PluginDescriptor* d = registry.find(ns.type);
    if (!d) {
      try {
        registry.get(ns.type);
      } catch (const ConfigError& e) {
        throw ConfigError(ns.where, (ns.is_loss ? "loss '" : "node '") + ns.name + "': " + e.what());
      }
    }
    b.desc = d;
    if (!d->create_node && !d->create_energy)
      throw ConfigError(ns.where, "node '" + ns.name + "': '" + ns.type + "' is a " + d->kind + ", not a graph node");
    if (ns.is_loss && d->kind != "loss" && d->kind != "energy")
      throw ConfigError(ns.where, "loss '" + ns.name + "' has type '" + ns.type + "', which is a " + d->kind +
                                      ", not a loss or an energy");
    const Params params(d->params, ns.params, b.label());
    try {
      b.node = registry.create_node(ns.type, params);
    } catch (...) {
      // A plugin's own check of its parameters (cnn1d's empty `channels`): at the node's line.
      rethrow_at(ns.where, (ns.is_loss ? "loss '" : "node '") + ns.name + "'");
    }
    for (const auto& p : d->outputs) b.out_ports.push_back(p.name);
    nodes.push_back(std::move(b));
  }
}

int Graph::Impl::existing_node(const std::string& name) const {
  const int n = node_index(name);
  if (n < 0) throw Error("the graph has no node named '" + name + "'");
  return n;
}

int Graph::Impl::node_index(const std::string& name) const {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].spec.name == name) return static_cast<int>(i);
  return -1;
}

int Graph::Impl::input_index(const std::string& name) const {
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (inputs[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> Graph::Impl::all_names() const {
  std::vector<std::string> v;
  for (const auto& n : nodes) v.push_back(n.spec.name);
  for (const auto& i : inputs) v.push_back(i.name);
  return v;
}

// Resolves a reference to a node output or a graph input (not to output aliases).
Source Graph::Impl::resolve(const GraphSpec& spec, const PortRef& r, const std::string& who, int depth) const {
  if (const int n = node_index(r.node); n >= 0) {
    const auto& ports = nodes[n].out_ports;
    if (r.port.empty()) return {n, 0, -1};
    auto it = std::find(ports.begin(), ports.end(), r.port);
    if (it == ports.end())
      throw ConfigError(r.where, who + ": " + nodes[n].label() + " has no output '" + r.port + "'" +
                                     did_you_mean(r.port, ports) + " (outputs: " + join(ports) + ")");
    return {n, static_cast<int>(it - ports.begin()), -1};
  }
  if (const int i = input_index(r.node); i >= 0) {
    if (!r.port.empty()) throw ConfigError(r.where, who + ": graph input '" + r.node + "' has no ports");
    return {-1, 0, i};
  }
  for (const auto& [name, ref] : spec.outputs)
    if (name == r.node && depth == 0 && r.port.empty()) return resolve(spec, ref, who, 1);
  const bool disabled = std::any_of(spec.nodes.begin(), spec.nodes.end(),
                                    [&](const NodeSpec& n) { return n.name == r.node; });
  throw ConfigError(r.where, who + ": unknown input '" + r.str() + "'" +
                                 (disabled ? " (it is a loss with weight 0)" : did_you_mean(r.node, all_names())));
}

// One node's inputs: positional, named, and (for losses) bound by port name.
void Graph::Impl::wire_node(const GraphSpec& spec, Built& b) const {
  const auto& declared = b.desc->inputs;
  std::vector<std::string> names;
  for (const auto& p : declared) names.push_back(p.name);
  std::vector<bool> connected(declared.size(), false);
  std::size_t positional = 0;
  for (const auto& [port, ref] : b.spec.inputs) {
    std::size_t k = 0;
    if (port.empty()) {
      if (positional >= declared.size())
        throw ConfigError(ref.where, b.label() + ": too many inputs; it takes " + std::to_string(declared.size()) +
                                         " (" + join(names) + ")");
      k = positional++;
    } else {
      auto it = std::find(names.begin(), names.end(), port);
      if (it == names.end())
        throw ConfigError(ref.where, b.label() + ": no input port '" + port + "'" + did_you_mean(port, names) +
                                         " (ports: " + join(names) + ")");
      k = static_cast<std::size_t>(it - names.begin());
    }
    if (connected[k]) throw ConfigError(ref.where, b.label() + ": input '" + names[k] + "' is connected twice");
    connected[k] = true;
    b.in_ports.push_back(names[k]);
    b.sources.push_back(resolve(spec, ref, b.label(), 0));
  }
  for (std::size_t k = 0; k < declared.size(); ++k) {
    if (connected[k]) continue;
    if (b.spec.is_loss) {
      PortRef implicit{names[k], "", b.spec.where};
      if (names[k] == "pred" || names[k] == "x") {
        if (spec.outputs.empty()) throw ConfigError(b.spec.where, b.label() + ": the graph has no outputs to bind 'pred' to");
        implicit = spec.outputs.front().second;
      }
      if (names[k] == "pred" || names[k] == "x" || input_index(names[k]) >= 0) {
        b.in_ports.push_back(names[k]);
        b.sources.push_back(resolve(spec, implicit, b.label(), 0));
        continue;
      }
    }
    if (!declared[k].optional)
      throw ConfigError(b.spec.where, b.label() + ": input '" + names[k] + "' is not connected (" + declared[k].doc + ")");
  }
}

// Wire inputs: positional, named, and (for losses) bound by port name.
void Graph::Impl::wire_inputs(const GraphSpec& spec) {
  // The outputs first: a loss reads the first of them by default, and an
  // output naming no node was blamed on that loss ("node 'l2' (l2): unknown
  // input 'shiftd'") instead of on the `outputs:` entry that names it.
  for (const auto& [name, ref] : spec.outputs) outputs.emplace_back(name, resolve(spec, ref, "output '" + name + "'", 0));
  for (auto& b : nodes) wire_node(spec, b);
}

// Topological order (depth-first), reporting a cycle as a path.
void Graph::Impl::sort_topologically() {
  const int count = static_cast<int>(nodes.size());
  std::vector<int> state(count, 0), order;
  std::vector<int> stack;
  std::function<void(int)> visit = [&](int n) {
    if (state[n] == 2) return;
    if (state[n] == 1) {
      std::string path;
      auto start = std::find(stack.begin(), stack.end(), n);
      for (auto it = start; it != stack.end(); ++it) path += nodes[*it].spec.name + " -> ";
      throw ConfigError(nodes[n].spec.where, "the graph has a cycle: " + path + nodes[n].spec.name);
    }
    state[n] = 1;
    stack.push_back(n);
    for (const auto& s : nodes[n].sources)
      if (s.node >= 0) visit(s.node);
    stack.pop_back();
    state[n] = 2;
    order.push_back(n);
  };
  for (int n = 0; n < count; ++n) visit(n);
  std::vector<int> position(count);
  for (int i = 0; i < count; ++i) position[order[i]] = i;
  std::vector<Built> sorted;
  for (int n : order) {
    sorted.push_back(std::move(nodes[n]));
    for (auto& s : sorted.back().sources)
      if (s.node >= 0) s.node = position[s.node];
  }
  nodes = std::move(sorted);
  for (auto& [name, s] : outputs)
    if (s.node >= 0) s.node = position[s.node];
}

// Shapes, in order; setup creates the weights.
void Graph::Impl::set_up_shapes(const GraphOptions& options) {
  for (auto& b : nodes) {
    ShapeMap in;
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) in[b.in_ports[k]] = shape_of(b.sources[k]);
    NodeContext ctx{b.spec.name, Fnv1a(options.seed * 0x9E3779B97F4A7C15ull + 1).text(b.spec.name).value(), options.assets,
                    options.garment_sizes};
    ShapeMap out;
    try {
      out = b.node->setup(in, ctx);
    } catch (const ConfigError& e) {
      std::string shapes;
      for (const auto& [p, s] : in) shapes += (shapes.empty() ? "" : ", ") + p + " " + s.str();
      throw ConfigError(b.spec.where, b.label() + ": " + e.what() + " (inputs: " + (shapes.empty() ? "none" : shapes) + ")");
    } catch (const std::bad_alloc&) {
      // Its weights (with their gradients) are allocated here: an mlp of
      // widths [65536] over 20,000 rows, each value in range, ended in a bare
      // "std::bad_alloc" naming no node (an outside check).
      std::size_t weights = 0;
      for (const auto& [name, w] : b.node->weights()) weights += static_cast<std::size_t>(w.value.size());
      throw ConfigError(b.spec.where, b.label() + ": its weights need more memory than this machine gives (" +
                                          std::to_string(weights) + " allocated before it ran out; each weight takes 8 "
                                          "bytes with its gradient): make its layers smaller");
    }
    for (const auto& p : b.out_ports) {
      auto it = out.find(p);
      if (it == out.end()) throw Error(b.label() + ": the plugin did not report the shape of output '" + p + "'");
      b.out_shapes.push_back(it->second);
    }
    if (b.spec.is_loss && !(b.out_shapes.size() == 1 && b.out_shapes[0] == Shape{1, 1}))
      throw ConfigError(b.spec.where, b.label() + ": a loss must have one output of shape [1, 1]");
    b.requires_grad = !b.node->weights().empty();
    for (const auto& s : b.sources)
      if (s.node >= 0 && nodes[s.node].requires_grad) b.requires_grad = true;
  }
}

// Which nodes each kind of run needs.
void Graph::Impl::mark_needed_nodes() {
  std::function<void(int, bool)> mark = [&](int n, bool loss) {
    bool& flag = loss ? nodes[n].for_losses : nodes[n].for_outputs;
    if (flag) return;
    flag = true;
    for (const auto& s : nodes[n].sources)
      if (s.node >= 0) mark(s.node, loss);
  };
  for (const auto& [name, s] : outputs)
    if (s.node >= 0) mark(s.node, false);
  for (int n = 0; n < static_cast<int>(nodes.size()); ++n)
    if (nodes[n].spec.is_loss) mark(n, true);
}

std::vector<Graph::NodeInfo> Graph::describe() const {
  std::vector<NodeInfo> out;
  for (const auto& b : impl_->nodes) {
    NodeInfo info{b.spec.name, b.spec.type, b.desc->kind, {}, {}, 0, b.spec.is_loss, b.spec.weight};
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) {
      const Source& s = b.sources[k];
      const std::string from = s.node >= 0 ? impl_->nodes[s.node].spec.name + "." + impl_->nodes[s.node].out_ports[s.port]
                                           : impl_->inputs[s.input].name;
      info.inputs.push_back(b.in_ports[k] + " <- " + from + " " + impl_->shape_of(s).str());
    }
    for (std::size_t k = 0; k < b.out_ports.size(); ++k) info.outputs.emplace_back(b.out_ports[k], b.out_shapes[k]);
    for (const auto& [name, w] : b.node->weights()) info.weight_count += w.value.size();
    out.push_back(std::move(info));
  }
  return out;
}

void Graph::forward(const std::map<std::string, Tensor>& inputs, bool with_losses) {
  impl_->set_inputs(inputs, with_losses, false);
  for (Impl::Built& b : impl_->nodes) b.forward_ms = 0.0;
  impl_->run([&](int n) { return impl_->nodes[n].for_outputs || (with_losses && impl_->nodes[n].for_losses); });
  impl_->ran_losses = with_losses;
}

void Graph::forward_until(const std::map<std::string, Tensor>& inputs, const std::string& node, bool reuse_unchanged) {
  Impl& g = *impl_;
  const std::vector<bool> after = g.fed_by(g.existing_node(node));
  const int last_batch = g.batch;
  const std::vector<bool> changed = g.set_inputs(inputs, false, reuse_unchanged);
  // Stale (run again): every node, unless the outputs may be kept; then a
  // node that reads a changed input, directly or through a node that does
  // (one pass in topological order), whose output was handed out to be
  // changed, or that has no outputs of this batch.
  std::vector<bool> stale(g.nodes.size(), true);
  if (reuse_unchanged && g.batch == last_batch)
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
      const Impl::Built& b = g.nodes[n];
      bool run = b.changed_in_place || b.outputs.size() != b.out_ports.size() ||
                 std::any_of(b.outputs.begin(), b.outputs.end(), [&](const Tensor& t) { return t.batch() != g.batch; });
      for (const Source& s : b.sources) run = run || (s.input >= 0 ? changed[s.input] : stale[s.node]);
      stale[n] = run;
    }
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
    if (stale[n]) g.nodes[n].forward_ms = 0.0;  // (a kept node keeps the time of the pass that made its outputs)
  g.run([&](int n) { return g.nodes[n].for_outputs && !after[n] && stale[n]; });
  g.ran_losses = false;
}

void Graph::forward_from(const std::string& node) {
  const std::vector<bool> after = impl_->fed_by(impl_->existing_node(node));
  impl_->run([&](int n) { return impl_->nodes[n].for_outputs && after[n]; });
}

bool Graph::input_read_before(const std::string& input, const std::string& node) const {
  const int i = impl_->input_index(input);
  if (i < 0) return false;
  const std::vector<bool> after = impl_->fed_by(impl_->existing_node(node));
  for (std::size_t n = 0; n < impl_->nodes.size(); ++n)
    if (impl_->nodes[n].for_outputs && !after[n])
      for (const Source& s : impl_->nodes[n].sources)
        if (s.input == i) return true;
  return false;
}

const Source& Graph::Impl::feeding(const std::string& node, const std::string& port) const {
  const Built& b = nodes[static_cast<std::size_t>(existing_node(node))];
  for (std::size_t k = 0; k < b.in_ports.size(); ++k) {
    if (b.in_ports[k] != port) continue;
    const Source& s = b.sources[k];
    if (s.node < 0) throw Error("node '" + node + "' port '" + port + "' reads the graph input '" + inputs[s.input].name + "'");
    return s;
  }
  throw Error("node '" + node + "' has no connected port '" + port + "'");
}

Tensor& Graph::fed_into(const std::string& node, const std::string& port) {
  const Source& s = impl_->feeding(node, port);
  Impl::Built& source = impl_->nodes[static_cast<std::size_t>(s.node)];
  source.changed_in_place = true;  // (maybe not the node's own output any more: run again, never kept)
  return source.outputs[s.port];
}

const Tensor& Graph::fed_into(const std::string& node, const std::string& port) const {
  const Source& s = impl_->feeding(node, port);
  return impl_->nodes[static_cast<std::size_t>(s.node)].outputs[s.port];
}

std::vector<bool> Graph::Impl::fed_by(int node) const {
  // Nodes are in topological order: one pass marks every node downstream.
  std::vector<bool> after(nodes.size(), false);
  after[node] = true;
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (const Source& s : nodes[n].sources)
      if (s.node >= 0 && after[s.node]) after[n] = true;
  return after;
}

std::vector<bool> Graph::Impl::set_inputs(const std::map<std::string, Tensor>& inputs, bool with_losses, bool compare) {
  Impl& g = *this;
  std::vector<bool> changed(g.inputs.size(), true);
  auto runs = [&](const Impl::Built& b) { return b.for_outputs || (with_losses && b.for_losses); };
  std::vector<bool> needed(g.inputs.size(), false);
  for (const auto& b : g.nodes)
    if (runs(b))
      for (const auto& s : b.sources)
        if (s.input >= 0) needed[s.input] = true;
  for (const auto& [name, s] : g.outputs)
    if (s.input >= 0) needed[s.input] = true;

  g.batch = -1;
  for (std::size_t i = 0; i < g.inputs.size(); ++i) {
    auto& in = g.inputs[i];
    auto it = inputs.find(in.name);
    if (it == inputs.end()) {
      if (needed[i]) throw ConfigError("graph input '" + in.name + "' " + in.shape.str() + " is required but was not given");
      continue;
    }
    const Tensor& t = it->second;
    if (t.shape() != in.shape)
      throw ConfigError("graph input '" + in.name + "' has " + std::to_string(t.rows()) + " x " + std::to_string(t.cols()) +
                        " per sample, but the graph expects " + std::to_string(in.shape.rows) + " x " +
                        std::to_string(in.shape.cols) + (in.shape.cols == 3 ? " (vertices x xyz)" : ""));
    if (g.batch >= 0 && t.batch() != g.batch)
      throw ConfigError("graph inputs disagree on the batch size (" + std::to_string(g.batch) + " vs " +
                        std::to_string(t.batch()) + " for '" + in.name + "')");
    g.batch = t.batch();
    // (Compared as bits: the same floats make the same outputs.)
    changed[i] = !compare || in.value.batch() != t.batch() || in.value.shape() != t.shape() ||
                 std::memcmp(in.value.data(), t.data(), t.size() * sizeof(float)) != 0;
    if (changed[i]) in.value = t;
  }
  if (g.batch <= 0) throw ConfigError("forward needs at least one input with a positive batch size");
  return changed;
}

void Graph::Impl::run(const std::function<bool(int)>& runs) {
  Impl& g = *this;
  for (int n = 0; n < static_cast<int>(g.nodes.size()); ++n) {
    Built& b = g.nodes[static_cast<std::size_t>(n)];
    if (!runs(n)) continue;  // (forward_from keeps the times of the nodes forward_until ran)
    TensorIn in;
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) in[b.in_ports[k]] = &g.value_of(b.sources[k]);
    b.outputs.resize(b.out_ports.size());
    TensorOut out;
    for (std::size_t k = 0; k < b.out_ports.size(); ++k) {
      b.outputs[k].resize(g.batch, b.out_shapes[k].rows, b.out_shapes[k].cols);
      out[b.out_ports[k]] = &b.outputs[k];
    }
    const auto start = std::chrono::steady_clock::now();
    b.changed_in_place = false;
    in_context(b.spec.type, [&] { b.node->forward(in, out); });  // errors name the node's plugin
    b.forward_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

std::vector<Graph::NodeTime> Graph::last_forward_times() const {
  std::vector<NodeTime> out;
  for (const auto& b : impl_->nodes)
    if (b.forward_ms > 0.0)
      out.push_back({b.spec.name, b.spec.type, b.forward_ms, b.node->flops_per_sample(), 0.0, b.spec.is_loss});
  return out;
}

std::vector<Graph::NodeTime> Graph::last_step_times() const {
  std::vector<NodeTime> out;
  for (const auto& b : impl_->nodes)
    if (b.forward_ms > 0.0 || b.backward_ms > 0.0)
      out.push_back(
          {b.spec.name, b.spec.type, b.forward_ms, b.node->flops_per_sample(), b.backward_ms, b.spec.is_loss});
  return out;
}

std::vector<std::string> Graph::gradient_ports(const std::string& node) const {
  for (const auto& b : impl_->nodes) {
    if (b.spec.name != node) continue;
    std::vector<std::string> ports;
    for (std::size_t k = 0; k < b.in_ports.size(); ++k)
      if (b.sources[k].node >= 0 && impl_->nodes[b.sources[k].node].requires_grad) ports.push_back(b.in_ports[k]);
    return ports;
  }
  throw Error("no node named '" + node + "'");
}

std::map<std::string, double> Graph::loss_terms() const {
  std::map<std::string, double> out;
  if (!impl_->ran_losses) return out;
  for (const auto& b : impl_->nodes) {
    if (!b.spec.is_loss) continue;
    double sum = 0.0;
    for (int i = 0; i < impl_->batch; ++i) sum += b.outputs[0](i, 0, 0);
    out[b.spec.name] = sum / impl_->batch;
  }
  return out;
}

double Graph::loss() const {
  double total = 0.0;
  const auto terms = loss_terms();
  for (const auto& b : impl_->nodes)
    if (b.spec.is_loss) total += b.spec.weight * terms.at(b.spec.name);
  return total;
}

namespace {
void run_backward(Graph::Impl& g) {
  for (auto it = g.nodes.rbegin(); it != g.nodes.rend(); ++it) {
    auto& b = *it;
    if (!b.requires_grad || !b.has_grad()) continue;
    const auto start = std::chrono::steady_clock::now();
    TensorIn in, out, gout;
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) in[b.in_ports[k]] = &g.value_of(b.sources[k]);
    for (std::size_t k = 0; k < b.out_ports.size(); ++k) {
      if (!b.grad_written[k]) b.out_grads[k].set_zero();  // an output no consumer took a gradient through
      out[b.out_ports[k]] = &b.outputs[k];
      gout[b.out_ports[k]] = &b.out_grads[k];
    }
    // Only the ports whose gradient reaches a weight (Caffe's propagate_down):
    // a graph input's or a constant's would be computed and thrown away.
    // The first consumer of an output writes its gradient straight into the
    // output's gradient buffer (Node::backward overwrites); later ones into a
    // temporary that is then added.
    std::vector<Tensor> gin(b.in_ports.size());
    std::vector<bool> direct(b.in_ports.size(), false);
    TensorOut gin_map;
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) {
      const auto& s = b.sources[k];
      if (s.node < 0 || !g.nodes[s.node].requires_grad) continue;
      auto& src = g.nodes[s.node];
      bool taken = src.grad_written[s.port];
      for (std::size_t j = 0; j < k && !taken; ++j)
        taken = direct[j] && b.sources[j].node == s.node && b.sources[j].port == s.port;
      if (!taken) {
        direct[k] = true;
        gin_map[b.in_ports[k]] = &src.out_grads[s.port];
        continue;
      }
      const Tensor& v = g.value_of(s);
      gin[k] = Tensor(v.batch(), v.rows(), v.cols());
      if (g.poison_gradient_buffers) gin[k].vec().setConstant(std::numeric_limits<float>::quiet_NaN());
      gin_map[b.in_ports[k]] = &gin[k];
    }
    in_context(b.spec.type, [&] { b.node->backward(in, out, gout, gin_map); });
    for (std::size_t k = 0; k < b.in_ports.size(); ++k) {
      const auto& s = b.sources[k];
      if (s.node < 0 || !g.nodes[s.node].requires_grad) continue;
      auto& src = g.nodes[s.node];
      if (!direct[k]) src.out_grads[s.port].vec() += gin[k].vec();
      src.grad_written[s.port] = true;
    }
    b.backward_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

void reset_grads(Graph::Impl& g) {
  for (auto& b : g.nodes) {
    b.backward_ms = 0.0;
    b.out_grads.resize(b.outputs.size());
    b.grad_written.assign(b.outputs.size(), false);
    // A node without weights upstream never runs backward: no gradient buffers.
    const bool used = b.requires_grad || b.spec.is_loss;
    // Buffers of the same size are kept as they are (not zeroed: see
    // grad_written): a fresh one of many MiB (the encoder's per-body-vertex
    // features) comes from mmap and costs page faults at every step, and
    // zeroing it cost a memset the first consumer then overwrote.
    for (std::size_t k = 0; k < b.outputs.size(); ++k) {
      Tensor& grad = b.out_grads[k];
      const Tensor& value = b.outputs[k];
      if (!used)
        grad = Tensor();
      else if (!(grad.batch() == value.batch() && grad.shape() == value.shape()))
        grad = Tensor(value.batch(), value.rows(), value.cols());
      if (used && g.poison_gradient_buffers) grad.vec().setConstant(std::numeric_limits<float>::quiet_NaN());
    }
  }
}
}  // namespace

void Graph::backward() {
  Impl& g = *impl_;
  if (!g.ran_losses) throw Error("backward() needs a forward() with losses first");
  reset_grads(g);
  for (auto& b : g.nodes) {
    if (!b.spec.is_loss) continue;
    std::fill(b.out_grads[0].data(), b.out_grads[0].data() + b.out_grads[0].size(),
              static_cast<float>(b.spec.weight / g.batch));
    b.grad_written[0] = true;
  }
  run_backward(g);
}

namespace {

// Reverse mode from `grad`, a gradient of the tensor `s` names (a node's
// output), into every weight upstream; `what` names the tensor in errors.
void backward_from_source(Graph::Impl& g, const Source& s, const Tensor& grad, const std::string& what) {
  reset_grads(g);
  if (s.node < 0) return;  // an input passed through: no weights involved
  Graph::Impl::Built& source = g.nodes[static_cast<std::size_t>(s.node)];
  const Tensor& value = source.outputs[s.port];
  if (value.shape() != grad.shape() || value.batch() != grad.batch())
    throw Error("backward: gradient " + grad.shape_str() + " does not match " + what + " " + value.shape_str());
  if (!source.requires_grad) return;  // no weights upstream of it
  Tensor& target = source.out_grads[s.port];  // (reset_grads sized it as the output)
  target.vec() = grad.vec();
  source.grad_written[s.port] = true;
  run_backward(g);
}

}  // namespace

void Graph::backward_from_output(const std::string& output, const Tensor& grad) {
  for (const auto& [name, s] : impl_->outputs)
    if (name == output) return backward_from_source(*impl_, s, grad, "output " + output);
  throw Error("backward_from_output: no output named '" + output + "'");
}

void Graph::backward_from_fed(const std::string& node, const std::string& port, const Tensor& grad) {
  backward_from_source(*impl_, impl_->feeding(node, port), grad, node + "." + port);  // (feeding refuses a graph input)
}

const Tensor& Graph::output(const std::string& name) const {
  for (const auto& [n, s] : impl_->outputs)
    if (n == name) return impl_->value_of(s);
  throw Error("no graph output named '" + name + "'" + did_you_mean(name, output_names()));
}

std::vector<std::string> Graph::output_names() const {
  std::vector<std::string> v;
  for (const auto& [n, s] : impl_->outputs) v.push_back(n);
  return v;
}

std::vector<std::string> Graph::input_names() const {
  std::vector<std::string> v;
  for (const auto& i : impl_->inputs) v.push_back(i.name);
  return v;
}

Shape Graph::input_shape(const std::string& name) const {
  for (const auto& i : impl_->inputs)
    if (i.name == name) return i.shape;
  throw Error("no graph input named '" + name + "'");
}

std::vector<std::pair<std::string, Weight*>> Graph::weights() {
  std::vector<std::pair<std::string, Weight*>> out;
  for (auto& b : impl_->nodes)
    for (auto& [name, w] : b.node->weights()) out.emplace_back(b.spec.name + "/" + name, &w);
  return out;
}

void Graph::zero_grad() {
  for (auto& b : impl_->nodes) b.node->zero_grad();
}

double Graph::flops_per_sample() const {
  double f = 0.0;
  for (const auto& b : impl_->nodes)
    if (b.for_outputs) f += b.node->flops_per_sample();
  return f;
}

}  // namespace drape
