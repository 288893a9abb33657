// `drape model set`: node parameters written into a model file (model_params.hpp).
#include <drape/training/model_params.hpp>

#include <drape/errors.hpp>
#include <drape/graph.hpp>
#include <drape/params.hpp>
#include <drape/registry.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/h5.hpp>
#include <drape/training/model_domain.hpp>

#include <yaml-cpp/yaml.h>

namespace fs = std::filesystem;

namespace drape {

std::vector<std::string> set_model_params(const Registry& registry, const fs::path& model_file,
                                          const Model::ParamOverrides& overrides, const fs::path& out) {
  if (overrides.empty()) throw ConfigError("nothing to set: give node.param=value");
  // Built and loaded with the overrides first: every check the graph and its
  // nodes make (the node exists, the value is one it takes, the weights still
  // fit) happens before anything is written. Its weights are the file's (all
  // or nothing) and are what is written back.
  Model model = Model::load(registry, model_file, overrides);
  Checkpoint c = model.checkpoint();
  YAML::Node graph = YAML::Load(c.graph);
  std::vector<std::string> changes;
  for (const auto& [node, params] : overrides) {
    YAML::Node spec = graph["nodes"][node];  // present: Model::load found it
    for (const auto& [key, value] : params) {
      const std::string before = spec["params"] && spec["params"][key] ? YAML::Dump(spec["params"][key]) : "(unset)";
      spec["params"][key] = YAML::Load(value);
      changes.push_back(node + "." + key + ": " + before + " -> " + YAML::Dump(spec["params"][key]));
    }
  }
  YAML::Emitter text;
  text << graph;
  c.graph = std::string(text.c_str()) + "\n";
  const std::optional<ModelDomain> domain = read_domain(model_file);
  write_atomically(out, [&](const fs::path& tmp) {
    save_checkpoint(tmp, model.graph().weights(), c);
    if (domain) {
      h5::File f = h5::File::open(tmp, h5::Access::ReadWrite);
      write_domain(f, *domain);
      f.close();
    }
  });
  return changes;
}

std::vector<PushOutSetting> push_out_settings(const Registry& registry, const std::string& graph_text,
                                              const std::string& name_for_errors) {
  std::vector<PushOutSetting> settings;
  for (const NodeSpec& node : parse_graph_text(graph_text, name_for_errors).nodes) {
    if (node.type != "push_out") continue;
    const Params params(registry.get(node.type).params, node.params, node.name);
    settings.push_back({node.name, params.get_bool("enabled"), params.get_float("epsilon"), params.get_bool("edges")});
  }
  return settings;
}

}  // namespace drape
