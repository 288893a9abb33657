// Changing a stored model's graph parameters that leave its weights alone
// (`drape model set`): what `--set node.param=value` does for one run of
// predict or eval, written into the model file so that every later use
// (predict, eval, optimize, Python) has it.
#pragma once

#include <drape/training/model.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace drape {

// A stored graph's YAML text with the overrides applied: node.param=value
// into the node's parameters, and node.in.port=ref connecting one of its
// input ports (an optional input the graph left unconnected, e.g.
// post.in.grade=garment_grade; the node's `in` must then be a map of
// ports). ConfigError naming `where` for an unknown node (with the close
// names). *changes (optional) gets one line per change, "node.key: old ->
// new" (old "(unset)" when the graph did not name it).
std::string graph_with_overrides(const std::string& graph_text, const Model::ParamOverrides& overrides,
                                 const std::string& where, std::vector<std::string>* changes = nullptr);

// Writes `out` (atomically; it may be `model_file`) as `model_file` with each
// override set in its stored graph's node parameters, its weights, metadata,
// history and domain unchanged. The changed graph is first built and given
// the weights (Model::load with the overrides), so a parameter that changes a
// weight's shape, an unknown node or a value the node refuses is a
// ConfigError and nothing is written. Returns one line per change, "node.param:
// old -> new" (old "(unset)" when the graph did not name it).
std::vector<std::string> set_model_params(const Registry& registry, const std::filesystem::path& model_file,
                                          const Model::ParamOverrides& overrides, const std::filesystem::path& out);

// The push-out (TailorNet's post-processing, the push_out node) a stored
// graph applies after the network, as the plugin reads its parameters
// (defaults filled in): what `drape model info` reports and what `drape
// bench accuracy-time` times with and without.
struct PushOutSetting {
  std::string node;
  bool enabled = false;
  double epsilon = 0;  // m
  bool edges = false;
  double strain_limit = 0;      // 0: off
  bool grade_connected = false; // the input grade connected (the limit then holds each size to its own pattern)
  bool mirror_average = false;  // the model averages the network's garment with its mirror twin before it
  bool untangle = false;        // the garment's crossings of itself undone after the push-out
};
std::vector<PushOutSetting> push_out_settings(const Registry& registry, const std::string& graph_text,
                                              const std::string& name_for_errors);
// The same of a graph already parsed (Model: the mirror average's node).
std::vector<PushOutSetting> push_out_settings(const Registry& registry, const GraphSpec& graph);

}  // namespace drape
