// Reading graph files: YAML -> GraphSpec, following `base:` chains.
#include <cmath>
#include <drape/graph.hpp>

#include "yaml_util.hpp"

#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace drape {
namespace {

PortRef parse_ref(const std::string& file, const YAML::Node& n) {
  const std::string text = yaml::scalar(file, n, "an input reference");
  PortRef r;
  r.where = yaml::at(file, n);
  const auto dot = text.find('.');
  r.node = text.substr(0, dot);
  if (dot != std::string::npos) r.port = text.substr(dot + 1);
  if (r.node.empty() || (dot != std::string::npos && r.port.empty()))
    throw ConfigError(r.where, "bad input reference '" + text + "': write `node` or `node.port`");
  return r;
}

std::vector<std::pair<std::string, PortRef>> parse_inputs(const std::string& file, const YAML::Node& n) {
  std::vector<std::pair<std::string, PortRef>> out;
  if (n.IsScalar()) {
    out.emplace_back("", parse_ref(file, n));
  } else if (n.IsSequence()) {
    for (const auto& e : n) out.emplace_back("", parse_ref(file, e));
  } else if (n.IsMap()) {
    for (const auto& kv : n) out.emplace_back(kv.first.as<std::string>(), parse_ref(file, kv.second));
  } else if (!n.IsNull()) {
    throw ConfigError(yaml::at(file, n), "`in` must be a reference, a list of references or a map port: reference");
  }
  return out;
}

double parse_weight(const std::string& file, const YAML::Node& n) {
  double w = 0;
  try {
    w = n.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(yaml::at(file, n), "a loss weight must be a number, got '" + (n.IsScalar() ? n.Scalar() : "?") + "'");
  }
  // (A negative weight would train the network to make that loss larger; 0
  // turns a loss off: Graph does not build it.)
  if (!std::isfinite(w) || w < 0)
    throw ConfigError(yaml::at(file, n), "a loss weight must be a finite number >= 0, got '" + n.Scalar() + "'");
  return w;
}

NodeSpec* find_node(GraphSpec& spec, const std::string& name) {
  for (auto& n : spec.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

// Applies a `nodes:` or `losses:` entry onto the spec (new node or override).
void apply_node(GraphSpec& spec, const std::string& file, const YAML::Node& key, const YAML::Node& body, bool loss) {
  const std::string name = key.as<std::string>();
  const SourceLocation where = yaml::at(file, key);
  NodeSpec* existing = find_node(spec, name);
  if (existing && existing->is_loss != loss) {
    // (A node of this very file was said to be "in the base graph": an outside check's file had no base.)
    const std::string whose = existing->where.file == file ? "at line " + std::to_string(existing->where.line) + " of this file"
                                                           : "in the base graph (" + existing->where.str() + ")";
    throw ConfigError(where, "'" + name + "' is a " + (loss ? "node" : "loss") + " " + whose + "; a " + (loss ? "loss" : "node") +
                                 " needs a name of its own");
  }
  if (body.IsNull()) {  // `name: null` or `name: ~` removes it
    if (!existing) {
      std::vector<std::string> names;
      for (const NodeSpec& n : spec.nodes)
        if (n.is_loss == loss) names.push_back(n.name);
      throw ConfigError(where, "cannot remove '" + name + "': the base graph has no such " + (loss ? "loss" : "node") +
                                   did_you_mean(name, names));
    }
    spec.nodes.erase(spec.nodes.begin() + (existing - spec.nodes.data()));
    return;
  }
  NodeSpec fresh;
  NodeSpec& n = existing ? *existing : fresh;
  n.name = name;
  n.is_loss = loss;
  n.where = where;
  if (loss && body.IsScalar()) {  // `name: weight`
    n.weight = parse_weight(file, body);
    if (!existing) n.type = name;
  } else if (body.IsMap()) {
    yaml::check_keys(file, body, loss ? std::vector<std::string>{"type", "in", "params", "weight"}
                                : std::vector<std::string>{"type", "in", "params"},
               (loss ? "loss '" : "node '") + name + "'");
    if (body["type"]) {
      const std::string type = yaml::scalar(file, body["type"], "`type`");
      if (existing && type != n.type) n.params.clear();  // another plugin: the old params mean nothing to it
      n.type = type;
    } else if (!existing) {
      if (!loss) {
        // An entry without a type overrides a node of the base graph: a
        // misspelt name is named as one (an outside check got "has no `type`" only).
        std::vector<std::string> nodes;
        for (const NodeSpec& other : spec.nodes)
          if (!other.is_loss) nodes.push_back(other.name);
        const std::string close = did_you_mean(name, nodes);
        throw ConfigError(where, "node '" + name + "' has no `type`" +
                                     (close.empty() ? std::string()
                                                    : " and overrides no node of the base graph" + close));
      }
      n.type = name;
    }
    if (body["in"]) n.inputs = parse_inputs(file, body["in"]);
    if (body["params"]) {
      for (auto& [k, v] : param_values_from_yaml(body["params"], file)) n.params[k] = v;
    }
    if (body["weight"]) n.weight = parse_weight(file, body["weight"]);
  } else {
    throw ConfigError(where, (loss ? "loss '" : "node '") + name + "' must be a map" + (loss ? " or a weight" : ""));
  }
  if (!existing) spec.nodes.push_back(std::move(fresh));
}

void apply_file(GraphSpec& spec, const fs::path& path, const YAML::Node& root, std::set<fs::path>& chain);

void apply_file(GraphSpec& spec, const fs::path& path, const YAML::Node& root, std::set<fs::path>& chain) {
  const std::string file = path.string();
  if (!root.IsMap()) throw ConfigError({file, 1}, "a graph file must be a YAML map (inputs, nodes, outputs, losses)");
  yaml::check_file_kind(file, root, "graph");
  yaml::check_keys(file, root, {"base", "description", "inputs", "nodes", "outputs", "losses"}, "graph");
  if (root["base"]) {
    const fs::path base = path.parent_path() / yaml::scalar(file, root["base"], "`base`");
    std::error_code ec;
    if (!fs::exists(base, ec)) throw ConfigError(yaml::at(file, root["base"]), "base graph '" + base.string() + "' does not exist");
    const fs::path canonical = fs::canonical(base);
    if (!chain.insert(canonical).second)
      throw ConfigError(yaml::at(file, root["base"]), "`base:` chain loops back to '" + base.string() + "'");
    apply_file(spec, base, yaml::load_file(base), chain);
  }
  if (const auto inputs = root["inputs"]) {
    if (!inputs.IsMap()) throw ConfigError(yaml::at(file, inputs), "`inputs` must be a map name: [rows, cols]");
    for (const auto& kv : inputs) {
      const auto name = kv.first.as<std::string>();
      if (!kv.second.IsSequence() || kv.second.size() != 2)
        throw ConfigError(yaml::at(file, kv.first), "input '" + name + "' needs a shape [rows, cols]");
      std::vector<std::string> dims;
      for (const auto& d : kv.second) dims.push_back(yaml::scalar(file, d, "a dimension"));
      auto it = std::find_if(spec.inputs.begin(), spec.inputs.end(), [&](auto& p) { return p.first == name; });
      if (it != spec.inputs.end()) it->second = {dims, yaml::at(file, kv.first)};
      else spec.inputs.push_back({name, {dims, yaml::at(file, kv.first)}});
    }
  }
  if (const auto nodes = root["nodes"]) {
    if (!nodes.IsMap()) throw ConfigError(yaml::at(file, nodes), "`nodes` must be a map name: {type, in, params}");
    for (const auto& kv : nodes) apply_node(spec, file, kv.first, kv.second, false);
  }
  if (const auto losses = root["losses"]) {
    if (!losses.IsMap()) throw ConfigError(yaml::at(file, losses), "`losses` must be a map name: weight or name: {type, in, weight}");
    for (const auto& kv : losses) apply_node(spec, file, kv.first, kv.second, true);
  }
  if (const auto outputs = root["outputs"]) {
    spec.outputs.clear();
    if (outputs.IsMap()) {
      for (const auto& kv : outputs) spec.outputs.emplace_back(kv.first.as<std::string>(), parse_ref(file, kv.second));
    } else {
      for (const auto& [port, ref] : parse_inputs(file, outputs)) spec.outputs.emplace_back(ref.node, ref);
    }
  }
}

// The resolved graph as YAML, without `base:` (what a checkpoint stores).
std::string emit(const GraphSpec& spec) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "inputs" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, dims] : spec.inputs)
    out << YAML::Key << name << YAML::Value << YAML::Flow << dims.first;
  out << YAML::EndMap;
  auto emit_nodes = [&](bool losses) {
    out << YAML::Key << (losses ? "losses" : "nodes") << YAML::Value << YAML::BeginMap;
    for (const auto& n : spec.nodes) {
      if (n.is_loss != losses) continue;
      out << YAML::Key << n.name << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "type" << YAML::Value << n.type;
      if (!n.inputs.empty()) {
        out << YAML::Key << "in" << YAML::Value << YAML::Flow;
        if (n.inputs.front().first.empty()) {  // positional, as written
          out << YAML::BeginSeq;
          for (const auto& [port, ref] : n.inputs) out << ref.str();
          out << YAML::EndSeq;
        } else {
          out << YAML::BeginMap;
          for (const auto& [port, ref] : n.inputs) out << YAML::Key << port << YAML::Value << ref.str();
          out << YAML::EndMap;
        }
      }
      if (!n.params.empty()) {
        out << YAML::Key << "params" << YAML::Value << YAML::Flow << YAML::BeginMap;
        for (const auto& [k, v] : n.params) out << YAML::Key << k << YAML::Value << v.node;
        out << YAML::EndMap;
      }
      if (losses) out << YAML::Key << "weight" << YAML::Value << n.weight;
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  };
  emit_nodes(false);
  emit_nodes(true);
  out << YAML::Key << "outputs" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, ref] : spec.outputs) out << YAML::Key << name << YAML::Value << ref.str();
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

// A graph's words: a node named as a graph input took the input's place in
// every node that read it (a loss's `body` fed the node's garment), and a '.'
// in a node's name cannot be referred to (node.port). Said where the node is
// written.
void check_names(const GraphSpec& spec) {
  for (const auto& [name, shape] : spec.inputs)
    if (name.find('.') != std::string::npos)
      throw ConfigError(shape.second, "input '" + name + "': a name cannot hold '.' (it separates a node from its port)");
  for (const NodeSpec& n : spec.nodes) {
    const char* what = n.is_loss ? "loss '" : "node '";
    if (n.name.find('.') != std::string::npos)
      throw ConfigError(n.where, what + n.name + "': a name cannot hold '.' (it separates a node from its port)");
    for (const auto& [name, shape] : spec.inputs)
      if (name == n.name)
        throw ConfigError(n.where, what + n.name + "' has the name of a graph input (" + shape.second.str() +
                                       "), which every node reading it would then read instead: rename one of them");
  }
}

}  // namespace

GraphSpec parse_graph_file(const fs::path& file) {
  GraphSpec spec;
  spec.file = file.string();
  std::set<fs::path> chain;
  std::error_code ec;
  if (fs::exists(file, ec)) chain.insert(fs::canonical(file));
  apply_file(spec, file, yaml::load_file(file), chain);
  check_names(spec);
  spec.text = emit(spec);
  return spec;
}

GraphSpec parse_graph_text(const std::string& yaml, const std::string& name_for_errors) {
  GraphSpec spec;
  spec.file = name_for_errors;
  const YAML::Node root = yaml::load_text(yaml, name_for_errors);
  if (root.IsMap() && root["base"]) throw ConfigError({name_for_errors, 1}, "`base:` is only allowed in graph files");
  std::set<fs::path> chain;
  apply_file(spec, name_for_errors, root, chain);
  check_names(spec);
  spec.text = emit(spec);
  return spec;
}

}  // namespace drape
