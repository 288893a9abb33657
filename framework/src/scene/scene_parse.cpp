// Reading scene files (see scene.hpp): YAML -> Scene, following `base:` chains.
#include <drape/io/shipped_files.hpp>
#include <drape/garment_grading.hpp>
#include <drape/materials/materials.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>

#include "../yaml_util.hpp"

#include <algorithm>
#include <map>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace drape {
namespace {

// Entries of `map` override `into`; a null value removes the entry.
void merge_values(ParamValues& into, const std::string& file, const YAML::Node& map, const std::string& owner) {
  if (!map || map.IsNull()) return;
  if (!map.IsMap()) throw ConfigError(yaml::at(file, map), owner + " must be a map of name: value");
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    if (kv.second.IsNull())
      into.erase(key);
    else
      into[key] = ParamValue{kv.second, yaml::at(file, kv.first)};
  }
}

// `garment: {grade: g}`: a number within the grading range, named with its file and line otherwise.
double parse_grade(const std::string& file, const YAML::Node& node) {
  double grade = 0;
  try {
    grade = node.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(yaml::at(file, node),
                      "garment `grade` must be a number (1: the garment as designed) or auto (each body's own grade)");
  }
  if (!(grade >= kMinGrade && grade <= kMaxGrade))
    throw ConfigError(yaml::at(file, node), "garment `grade` " + yaml::scalar(file, node, "grade") + " is outside " +
                                                "0.5 to 2 (a tailor's grade scales girths and lengths by this factor)");
  return grade;
}

void set_effect(Scene& s, const std::string& name, ParamValues params, const SourceLocation& where) {
  auto it = std::find_if(s.effects.begin(), s.effects.end(), [&](const SceneEffect& e) { return e.name == name; });
  if (it == s.effects.end())
    s.effects.push_back({name, std::move(params), where});
  else
    *it = {name, std::move(params), where};
}

// A solver setting written among the effects (`effects: {morph_steps: 4}`)
// is named as one, before its value is read as an effect's parameters.
void refuse_solver_key_as_effect(const std::string& file, const YAML::Node& key) {
  const std::string name = key.as<std::string>();
  for (const ParamSpec& p : scene_solver_specs())
    if (p.name == name)
      throw ConfigError(yaml::at(file, key), "'" + name + "' is a solver setting, not an effect: write it under `solver:`");
}

void parse_effects(Scene& s, const std::string& file, const YAML::Node& n) {
  if (n.IsSequence()) {  // a list replaces the base's effects
    s.effects.clear();
    std::map<std::string, YAML::Node> listed;  // name -> where: an effect listed twice is refused, as the map form's key
    for (const auto& e : n) {
      const YAML::Node name_node = e.IsMap() && e.size() == 1 ? e.begin()->first : e;
      if (name_node.IsScalar()) {
        const auto [first, fresh] = listed.emplace(name_node.Scalar(), name_node);
        if (!fresh)
          throw ConfigError(yaml::at(file, name_node), "effect '" + name_node.Scalar() + "' is listed twice (first at line " +
                                                           std::to_string(first->second.Mark().line + 1) +
                                                           "): list each effect once, with its parameters");
      }
      if (e.IsScalar()) {
        set_effect(s, e.Scalar(), {}, yaml::at(file, e));
      } else if (e.IsMap() && e.size() == 1) {
        const auto kv = *e.begin();
        refuse_solver_key_as_effect(file, kv.first);
        ParamValues p;
        merge_values(p, file, kv.second, "effect '" + kv.first.as<std::string>() + "'");
        set_effect(s, kv.first.as<std::string>(), std::move(p), yaml::at(file, kv.first));
      } else {
        throw ConfigError(yaml::at(file, e), "an effect is a name or `name: {params}`");
      }
    }
  } else if (n.IsMap()) {  // a map adds, overrides or (with null) removes single effects
    for (const auto& kv : n) {
      const auto name = kv.first.as<std::string>();
      refuse_solver_key_as_effect(file, kv.first);
      if (kv.second.IsNull()) {  // `name: null` (or `name:`) removes it; `name: {}` adds it with defaults
        // One the scene does not have: a misspelt removal left the effect
        // running without a word (`self_contat: null`, an outside check).
        const auto it = std::find_if(s.effects.begin(), s.effects.end(), [&](const SceneEffect& e) { return e.name == name; });
        if (it == s.effects.end()) {
          std::vector<std::string> names;
          std::string list;
          for (const SceneEffect& e : s.effects) names.push_back(e.name), list += (list.empty() ? "" : ", ") + e.name;
          throw ConfigError(yaml::at(file, kv.first), "`" + name + ": null` removes effect '" + name +
                                                          "', which the scene does not have" + did_you_mean(name, names) +
                                                          " (it has: " + (list.empty() ? "none" : list) + ")");
        }
        s.effects.erase(it);
        continue;
      }
      auto existing = std::find_if(s.effects.begin(), s.effects.end(), [&](const SceneEffect& e) { return e.name == name; });
      ParamValues p = existing == s.effects.end() ? ParamValues{} : existing->params;
      merge_values(p, file, kv.second, "effect '" + name + "'");
      set_effect(s, name, std::move(p), yaml::at(file, kv.first));
    }
  } else {
    throw ConfigError(yaml::at(file, n), "`effects` must be a list of energy names or a map name: {params}");
  }
}

void apply(Scene& s, const fs::path& path, const std::string& file, const YAML::Node& root, std::vector<fs::path>& chain) {
  if (!root || root.IsNull()) return;
  yaml::check_file_kind(file, root, "scene");
  yaml::check_keys(file, root, {"base", "description", "body", "garment", "materials", "effects", "solver"}, "scene");
  if (root["base"]) {
    if (path.empty()) throw ConfigError(yaml::at(file, root["base"]), "`base:` needs a scene file (relative to it)");
    const fs::path named = yaml::scalar(file, root["base"], "`base`");
    fs::path base = path.parent_path() / named;
    std::error_code ec;
    if (!fs::exists(base, ec)) {
      // A user's scene elsewhere may name a shipped one, by its path in the
      // source tree or by its name among the shipped scenes (it said only
      // "does not exist": an outside check's `base: tshirt_coarse.yaml`).
      fs::path shipped;
      if (named.is_relative()) {
        shipped = locate_shipped_file(named);
        if (shipped.empty()) shipped = locate_shipped_file(fs::path("graphs/scenes") / named);
      }
      if (shipped.empty()) {
        std::string where = path.parent_path().empty() ? std::string(".") : path.parent_path().string();
        if (named.is_relative())
          for (const auto& dir : shipped_data_dirs()) where += ", " + (dir / "graphs/scenes").string() + ", " + dir.string();
        throw ConfigError(yaml::at(file, root["base"]), "base scene '" + named.string() + "' does not exist (looked in " + where + ")");
      }
      base = shipped;
    }
    const fs::path canonical = fs::canonical(base);
    if (std::find(chain.begin(), chain.end(), canonical) != chain.end())
      throw ConfigError(yaml::at(file, root["base"]), "`base:` chain loops back to '" + base.string() + "'");
    chain.push_back(canonical);
    apply(s, base, base.string(), yaml::load_file(base), chain);
  }
  if (root["description"]) s.description = yaml::scalar(file, root["description"], "`description`");
  if (const YAML::Node body = root["body"]) {
    yaml::check_keys(file, body, {"model", "params", "shape", "pose"}, "body");
    if (body["model"]) {
      const std::string model = yaml::scalar(file, body["model"], "body `model`");
      if (model != s.body_model) s.body_params.clear();  // another model's parameters do not carry over
      s.body_model = model;
      s.body_model_where = yaml::at(file, body["model"]);
    }
    merge_values(s.body_params, file, body["params"], "body `params`");
    merge_values(s.shape, file, body["shape"], "body `shape`");
    // Joint angles in degrees by name (docs/poses.md); checked against the
    // body model's pose space when the scene is built (Simulation).
    merge_values(s.pose, file, body["pose"], "body `pose`");
  }
  if (const YAML::Node garment = root["garment"]) {
    yaml::check_keys(file, garment, {"template", "params", "grade"}, "garment");
    if (garment["template"]) {
      const std::string t = yaml::scalar(file, garment["template"], "garment `template`");
      if (t != s.garment) s.garment_params.clear();
      s.garment = t;
      s.garment_where = yaml::at(file, garment["template"]);
    }
    merge_values(s.garment_params, file, garment["params"], "garment `params`");
    if (const YAML::Node grade = garment["grade"]) {
      s.garment_grade_auto = grade.IsScalar() && grade.Scalar() == "auto";
      s.garment_grade = s.garment_grade_auto ? 1.0 : parse_grade(file, grade);
    }
  }
  if (const YAML::Node materials = root["materials"]) {
    if (!materials.IsMap()) throw ConfigError(yaml::at(file, materials), "`materials` must be a map region: preset");
    for (const auto& kv : materials) {
      const auto region = kv.first.as<std::string>();
      auto it = std::find_if(s.materials.begin(), s.materials.end(), [&](const SceneMaterial& m) { return m.region == region; });
      if (kv.second.IsNull()) {
        if (it != s.materials.end()) {
          s.dropped_materials.push_back(*it);
          s.dropped_materials.back().where = yaml::at(file, kv.first);
          s.materials.erase(it);
        }
        continue;
      }
      SceneMaterial m{region, kv.second, file, yaml::at(file, kv.first)};
      if (it == s.materials.end())
        s.materials.push_back(std::move(m));
      else
        *it = std::move(m);
    }
  }
  if (const YAML::Node effects = root["effects"]) {
    // `effects: null` (or `effects:` with nothing under it) kept the base's
    // effects without a word (an outside check): named at its key.
    if (effects.IsNull())
      for (const auto& kv : root)
        if (kv.first.IsScalar() && kv.first.Scalar() == "effects")
          throw ConfigError(yaml::at(file, kv.first), "`effects` has nothing under it: give a list of energy names or a "
                                                      "map name: {params} (in a derived scene, a map entry `name: null` "
                                                      "removes one effect of the base)");
    parse_effects(s, file, effects);
  }
  merge_values(s.solver, file, root["solver"], "`solver`");
}

YAML::Node values_yaml(const ParamValues& values) {
  YAML::Node n(YAML::NodeType::Map);
  for (const auto& [k, v] : values) n[k] = v.node;
  return n;
}

}  // namespace

bool Scene::has_effect(const std::string& name) const {
  return std::any_of(effects.begin(), effects.end(), [&](const SceneEffect& e) { return e.name == name; });
}

std::string Scene::yaml() const {
  YAML::Emitter out;
  out << YAML::BeginMap;
  if (!description.empty()) out << YAML::Key << "description" << YAML::Value << description;
  out << YAML::Key << "body" << YAML::Value << YAML::BeginMap << YAML::Key << "model" << YAML::Value << body_model
      << YAML::Key << "params" << YAML::Value << YAML::Flow << values_yaml(body_params) << YAML::Key << "shape"
      << YAML::Value << YAML::Flow << values_yaml(shape);
  // Written only when posed, so the text of an A-pose scene is what it always was.
  if (!pose.empty()) out << YAML::Key << "pose" << YAML::Value << YAML::Flow << values_yaml(pose);
  out << YAML::EndMap;
  out << YAML::Key << "garment" << YAML::Value << YAML::BeginMap << YAML::Key << "template" << YAML::Value << garment
      << YAML::Key << "params" << YAML::Value << YAML::Flow << values_yaml(garment_params);
  // Written only when graded, so the scene text of an ungraded garment is what it always was.
  if (garment_grade_auto)
    out << YAML::Key << "grade" << YAML::Value << "auto";
  else if (garment_grade != 1.0)
    out << YAML::Key << "grade" << YAML::Value << garment_grade;
  out << YAML::EndMap;
  out << YAML::Key << "materials" << YAML::Value << YAML::BeginMap;
  // A material file is named relative to its scene; the text goes elsewhere
  // (datasets), so it carries the file's data instead of the path.
  for (const auto& m : materials)
    out << YAML::Key << m.region << YAML::Value << YAML::Flow << self_contained_material_spec(m.spec, m.file);
  out << YAML::EndMap;
  out << YAML::Key << "effects" << YAML::Value << YAML::BeginMap;
  for (const auto& e : effects) out << YAML::Key << e.name << YAML::Value << YAML::Flow << values_yaml(e.params);
  out << YAML::EndMap;
  out << YAML::Key << "solver" << YAML::Value << YAML::Flow << values_yaml(solver);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

Scene load_scene(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw ConfigError("scene file '" + file.string() + "' does not exist");
  Scene s;
  s.file = file.string();
  std::vector<fs::path> chain{fs::canonical(file)};
  const YAML::Node root = yaml::load_file(file);
  // (It said "the scene names no effects" of a file with nothing in it.)
  if (root.IsNull())
    throw ConfigError(file.string() + ": the file is empty (or only comments): a scene names at least its effects "
                      "(docs/scenes.md)");
  apply(s, file, file.string(), root, chain);
  return s;
}

Scene parse_scene(const std::string& text, const std::string& name_for_errors) {
  Scene s;
  s.file = name_for_errors;
  std::vector<fs::path> chain;
  apply(s, {}, name_for_errors, yaml::load_text(text, name_for_errors), chain);
  return s;
}

}  // namespace drape
