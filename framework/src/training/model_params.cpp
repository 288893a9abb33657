// `drape model set`: node parameters written into a model file (model_params.hpp).
#include <drape/training/model_params.hpp>

#include <drape/errors.hpp>
#include <drape/graph.hpp>
#include <drape/params.hpp>
#include <drape/registry.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/training/model_domain.hpp>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace drape {

std::string graph_with_overrides(const std::string& graph_text, const Model::ParamOverrides& overrides,
                                 const std::string& where, std::vector<std::string>* changes) {
  YAML::Node graph = YAML::Load(graph_text);
  for (const auto& [node, params] : overrides) {
    YAML::Node spec = graph["nodes"][node];
    if (!spec) {
      std::vector<std::string> names;
      for (const auto& kv : graph["nodes"]) names.push_back(kv.first.as<std::string>());
      throw ConfigError(where + ": the model's graph has no node '" + node + "' to change" + did_you_mean(node, names));
    }
    for (const auto& [key, value] : params) {
      if (key.rfind("in.", 0) == 0) {
        const std::string port = key.substr(3);
        if (port.empty()) throw ConfigError(where + ": " + node + ".in.: name the input port, e.g. " + node + ".in.grade=garment_grade");
        if (spec["in"] && !spec["in"].IsMap())
          throw ConfigError(where + ": node '" + node + "' takes its inputs by position, not by port: " + node + "." + key +
                            " cannot connect one");
        const std::string before = spec["in"] && spec["in"][port] ? spec["in"][port].as<std::string>() : "(unset)";
        spec["in"][port] = value;
        if (changes) changes->push_back(node + "." + key + ": " + before + " -> " + value);
        continue;
      }
      const std::string before = spec["params"] && spec["params"][key] ? YAML::Dump(spec["params"][key]) : "(unset)";
      spec["params"][key] = YAML::Load(value);
      if (changes) changes->push_back(node + "." + key + ": " + before + " -> " + YAML::Dump(spec["params"][key]));
    }
  }
  YAML::Emitter text;
  text << graph;
  return std::string(text.c_str()) + "\n";
}

std::vector<std::string> set_model_params(const Registry& registry, const fs::path& model_file,
                                          const Model::ParamOverrides& overrides, const fs::path& out) {
  if (overrides.empty()) throw ConfigError("nothing to set: give node.param=value");
  // Built and loaded with the overrides first: every check the graph and its
  // nodes make (the node exists, the value is one it takes, the weights still
  // fit) happens before anything is written. Its weights are the file's (all
  // or nothing) and are what is written back.
  Model model = Model::load(registry, model_file, overrides);
  // A node with learnt weights computes what it was trained to only with the
  // parameters it was trained with: another stride or activation keeps every
  // weight's shape and gives another garment, silently. `--set` for one run
  // (predict, eval) stays open for such experiments; a stored model does not.
  std::set<std::string> learnt;
  for (const auto& [name, weight] : model.graph().weights()) learnt.insert(name.substr(0, name.find('/')));
  for (const auto& [node, params] : overrides)
    if (learnt.count(node))
      throw ConfigError(model_file.string() + ": " + node + "." + params.begin()->first + ": node '" + node +
                        "' has learnt weights, and they were trained with its parameters as they are: a changed one "
                        "changes what they compute. Give --set to predict or eval to try it for one run, or train again; "
                        "model set stores parameters of nodes without weights (e.g. the push-out 'post')");
  Checkpoint c = model.checkpoint();
  std::vector<std::string> changes;
  c.graph = graph_with_overrides(c.graph, overrides, model_file.string(), &changes);
  save_model_file(out, model.graph().weights(), c, read_domain(model_file));
  return changes;
}

std::vector<PushOutSetting> push_out_settings(const Registry& registry, const std::string& graph_text,
                                              const std::string& name_for_errors) {
  return push_out_settings(registry, parse_graph_text(graph_text, name_for_errors));
}

std::vector<PushOutSetting> push_out_settings(const Registry& registry, const GraphSpec& graph) {
  std::vector<PushOutSetting> settings;
  for (const NodeSpec& node : graph.nodes) {
    if (node.type != "push_out") continue;
    const Params params(registry.get(node.type).params, node.params, node.name);
    const bool grade = std::any_of(node.inputs.begin(), node.inputs.end(), [](const auto& in) { return in.first == "grade"; });
    settings.push_back({node.name, params.get_bool("enabled"), params.get_float("epsilon"), params.get_bool("edges"),
                        params.get_float("strain_limit"), grade, params.get_bool("mirror_average"),
                        params.get_bool("untangle")});
  }
  return settings;
}

}  // namespace drape
