// Reading MakeHuman's rig files (rig_files.hpp). They are JSON, which
// yaml-cpp reads as YAML (JSON is a subset of YAML 1.2).
#include "rig_files.hpp"

#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <type_traits>

namespace fs = std::filesystem;

namespace drape::makehuman {
namespace {

constexpr const char* kSkeleton = "default.mhskel";
constexpr const char* kDefaultWeights = "default_weights.mhw";

YAML::Node load_json(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError("cannot read MakeHuman rig file '" + file.string() + "'");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return YAML::Load(text.str());
  } catch (const YAML::Exception& e) {
    throw ConfigError(file.string() + ": not JSON (line " + std::to_string(e.mark.line + 1) + ": " + e.msg + ")");
  }
}

// `node[key]` of the given kind, or a ConfigError naming file and key.
YAML::Node member(const YAML::Node& node, const std::string& key, YAML::NodeType::value type, const fs::path& file,
                  const std::string& where) {
  const YAML::Node m = node.IsMap() ? node[key] : YAML::Node();
  if (!m || m.Type() != type) {
    const char* kind = type == YAML::NodeType::Map ? "an object" : type == YAML::NodeType::Sequence ? "a list" : "a string";
    throw ConfigError(file.string() + ": " + where + " needs \"" + key + "\" as " + kind);
  }
  return m;
}

template <class T>
T scalar(const YAML::Node& n, const fs::path& file, const std::string& where) {
  try {
    if (!n.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "");
    return n.as<T>();
  } catch (const YAML::Exception&) {
    throw ConfigError(file.string() + ": " + where + " is not a " + (std::is_same_v<T, int> ? "vertex index" : "number"));
  }
}

int vertex_index(const YAML::Node& n, int num_base_vertices, const fs::path& file, const std::string& where) {
  const int v = scalar<int>(n, file, where);
  if (v < 0 || v >= num_base_vertices)
    throw ConfigError(file.string() + ": " + where + " refers to vertex " + std::to_string(v) + ", the base mesh has " +
                      std::to_string(num_base_vertices));
  return v;
}

// Bones in an order with every parent before its children (depth first from
// the root, children by name), as drape's skinning composes them.
std::vector<RigFiles::Bone> parents_first(std::map<std::string, RigFiles::Bone> bones, const fs::path& file) {
  std::map<std::string, std::vector<std::string>> children;
  std::vector<std::string> roots;
  for (const auto& [name, b] : bones) {
    if (b.parent.empty())
      roots.push_back(name);
    else if (!bones.count(b.parent))
      throw ConfigError(file.string() + ": bone \"" + name + "\" has parent \"" + b.parent + "\", which is no bone");
    else
      children[b.parent].push_back(name);
  }
  if (roots.size() != 1) throw ConfigError(file.string() + ": " + std::to_string(roots.size()) + " bones without a parent, expected one root");
  std::vector<RigFiles::Bone> out;
  std::function<void(const std::string&)> visit = [&](const std::string& name) {
    out.push_back(bones.at(name));
    for (const std::string& c : children[name]) visit(c);
  };
  visit(roots.front());
  if (out.size() != bones.size()) throw ConfigError(file.string() + ": the bones' parents form a cycle");
  return out;
}

}  // namespace

std::string missing_rig_files(const fs::path& root) {
  const fs::path dir = root / "rigs";
  std::vector<std::string> missing;
  for (const char* f : {kSkeleton, kDefaultWeights})
    if (!fs::exists(dir / f)) missing.push_back((dir / f).string());
  if (missing.empty()) return "";
  std::string list = missing.front() + (missing.size() > 1 ? " and " + missing.back() : "");
  return "no MakeHuman rig, so it cannot be posed: " + list + (missing.size() > 1 ? " are" : " is") +
         " missing (MakeHuman's CC0 rig: makehuman/data/rigs/ of github.com/makehumancommunity/makehuman, unmodified; "
         "docs/poses.md)";
}

RigFiles read_rig_files(const fs::path& root, int num_base_vertices) {
  RigFiles rig;
  rig.skeleton_file = root / "rigs" / kSkeleton;
  const YAML::Node skel = load_json(rig.skeleton_file);
  const fs::path& sf = rig.skeleton_file;
  if (!skel.IsMap()) throw ConfigError(sf.string() + ": expected a JSON object with \"bones\" and \"joints\"");

  for (const auto& kv : member(skel, "joints", YAML::NodeType::Map, sf, "the skeleton")) {
    const std::string name = kv.first.as<std::string>();
    const std::string where = "joint \"" + name + "\"";
    if (!kv.second.IsSequence() || kv.second.size() == 0) throw ConfigError(sf.string() + ": " + where + " needs a list of vertex indices");
    std::vector<int>& ids = rig.joints[name];
    for (const auto& v : kv.second) ids.push_back(vertex_index(v, num_base_vertices, sf, where));
  }

  std::map<std::string, RigFiles::Bone> bones;
  for (const auto& kv : member(skel, "bones", YAML::NodeType::Map, sf, "the skeleton")) {
    RigFiles::Bone b;
    b.name = kv.first.as<std::string>();
    const std::string where = "bone \"" + b.name + "\"";
    b.head = member(kv.second, "head", YAML::NodeType::Scalar, sf, where).as<std::string>();
    b.tail = member(kv.second, "tail", YAML::NodeType::Scalar, sf, where).as<std::string>();
    for (const std::string* j : {&b.head, &b.tail})
      if (!rig.joints.count(*j)) throw ConfigError(sf.string() + ": " + where + " names joint \"" + *j + "\", which \"joints\" does not define");
    const YAML::Node parent = kv.second["parent"];
    if (parent && !parent.IsNull()) {
      if (!parent.IsScalar()) throw ConfigError(sf.string() + ": " + where + ": \"parent\" must be a bone name or null");
      b.parent = parent.as<std::string>();
    }
    bones[b.name] = b;
  }
  if (bones.empty()) throw ConfigError(sf.string() + ": \"bones\" is empty");
  rig.bones = parents_first(std::move(bones), sf);

  const YAML::Node wf = skel["weights_file"];
  rig.weights_file = root / "rigs" / (wf && wf.IsScalar() ? wf.as<std::string>() : std::string(kDefaultWeights));
  const YAML::Node weights = load_json(rig.weights_file);
  const fs::path& wfile = rig.weights_file;
  std::set<std::string> names;
  for (const auto& b : rig.bones) names.insert(b.name);
  for (const auto& kv : member(weights, "weights", YAML::NodeType::Map, wfile, "the weights file")) {
    const std::string bone = kv.first.as<std::string>();
    const std::string where = "bone \"" + bone + "\"";
    if (!names.count(bone)) throw ConfigError(wfile.string() + ": weights for " + where + ", which " + sf.filename().string() + " does not have");
    if (!kv.second.IsSequence()) throw ConfigError(wfile.string() + ": " + where + " needs a list of [vertex, weight] pairs");
    auto& list = rig.weights[bone];
    for (const auto& pair : kv.second) {
      if (!pair.IsSequence() || pair.size() != 2) throw ConfigError(wfile.string() + ": " + where + " needs [vertex, weight] pairs");
      const int v = vertex_index(pair[0], num_base_vertices, wfile, where);
      const double w = scalar<double>(pair[1], wfile, where + "'s weight of vertex " + std::to_string(v));
      if (!(std::isfinite(w) && w >= 0))
        throw ConfigError(wfile.string() + ": " + where + " gives vertex " + std::to_string(v) + " the weight " + std::to_string(w));
      list.emplace_back(v, w);
    }
  }
  return rig;
}

}  // namespace drape::makehuman
