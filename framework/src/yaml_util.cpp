#include "yaml_util.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <vector>
#include <sstream>

namespace drape::yaml {

SourceLocation at(const std::string& file, const YAML::Node& n) { return {file, n ? n.Mark().line + 1 : 0}; }

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : separator) + i;
  return s;
}

std::string scalar(const std::string& file, const YAML::Node& n, const std::string& what) {
  if (!n.IsScalar()) throw ConfigError(at(file, n), what + " must be a single value");
  return n.Scalar();
}

void check_keys(const std::string& file, const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& owner) {
  if (!map.IsMap()) throw ConfigError(at(file, map), owner + " must be a map");
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      throw ConfigError(at(file, kv.first), owner + ": unknown key '" + key + "'" + did_you_mean(key, allowed) +
                                                " (allowed: " + joined(allowed) + ")");
  }
}

namespace {

// yaml-cpp keeps one of two equal keys of a map without a word, so a scene
// with two `garment:` entries would lose one silently; every map of a
// document is checked once, as it is loaded.
// `open` holds the nodes being walked, outermost first: an alias of a node
// inside that node itself (`a: &x [*x]`) makes the document an endless tree,
// which every reader after this one would walk until the stack overflows.
void refuse_repeated_keys(const YAML::Node& node, const std::string& file, std::vector<YAML::Node>& open) {
  if (!node.IsSequence() && !node.IsMap()) return;
  for (const YAML::Node& outer : open)
    if (outer.is(node))
      throw ConfigError({file, node.Mark().line + 1},
                        "a recursive alias: this node contains itself (an anchor '&name' used as '*name' inside the node "
                        "it names); write the repeated part out");
  open.push_back(node);
  if (node.IsSequence())
    for (const auto& item : node) refuse_repeated_keys(item, file, open);
  if (node.IsMap()) {
    std::map<std::string, int> seen;  // key -> 1-based line
    for (const auto& kv : node) {
      if (kv.first.IsScalar()) {
        const std::string key = kv.first.Scalar();
        const int line = kv.first.Mark().line + 1;
        const auto [it, fresh] = seen.emplace(key, line);
        if (!fresh)
          throw ConfigError({file, line}, "'" + key + "' is defined twice (first at line " + std::to_string(it->second) +
                                              "); one map keeps one key once: merge the two");
      }
      refuse_repeated_keys(kv.first, file, open);
      refuse_repeated_keys(kv.second, file, open);
    }
  }
  open.pop_back();
}

}  // namespace

YAML::Node load_text(const std::string& text, const std::string& name_for_errors) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError({name_for_errors, e.mark.line + 1}, "malformed YAML: " + e.msg);
  }
  std::vector<YAML::Node> open;
  refuse_repeated_keys(root, name_for_errors, open);
  return root;
}

YAML::Node load_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read '" + path.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return load_text(ss.str(), path.string());
}

}  // namespace drape::yaml
