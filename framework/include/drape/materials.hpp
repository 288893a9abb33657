#pragma once
// Named cloth materials read from YAML (format: docs/materials.md). The presets
// shipped in graphs/materials/presets.yaml are compiled into the library
// (MaterialTable::builtin()); users add or replace presets with their own file:
//
//   MaterialTable table = MaterialTable::builtin();
//   table.merge(MaterialTable::load("my_materials.yaml"));
//   Material knit = table.get("gray-interlock");
//
// A preset either sets every physical field or names a `base:` preset and
// scales (`multipliers:`) or replaces fields of it. Bases are looked up when a
// preset is resolved (get/resolve), in the table as it is then, so a preset of
// one file may build on a preset of another and a merged file may replace a base
// for everything built on it.
#include <drape/energy.hpp>
#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drape {

// One preset as written in its file, validated field by field but not resolved.
struct MaterialPreset {
  std::string name;  // empty for an inline material
  std::string doc;
  SourceLocation where;  // the preset's name (or the inline map)

  std::string base;  // empty: the preset sets every field itself
  SourceLocation base_where;

  // Fields the preset sets, each with where it was written.
  std::optional<double> density, bending, thickness;
  std::optional<Eigen::Vector4d> stretch;
  std::map<std::string, SourceLocation> field_where;  // "density", "stretch", ...

  // Factors applied to the base's values (1 when not given; only with a base).
  double stretch_multiplier = 1, bend_multiplier = 1, density_multiplier = 1, thickness_multiplier = 1;
};

class MaterialTable {
 public:
  // The presets of graphs/materials/presets.yaml, embedded at build time.
  static MaterialTable builtin();
  // A preset file. ConfigError (file:line and key) for a malformed file, an
  // unknown key or a bad value; bases are checked when resolved (see check()).
  static MaterialTable load(const std::filesystem::path& path);
  // The same from YAML text; `file` names it in error messages.
  static MaterialTable parse(const std::string& yaml_text, const std::string& file);

  // Adds other's presets; a name in both takes other's (the later one wins).
  void merge(const MaterialTable& other);

  // The resolved material (Material::name = `name`). ConfigError listing close
  // names for an unknown one; ConfigError at the preset's file:line for an
  // unknown base, a cycle of bases (showing it) or a stretch that is not
  // positive definite after resolution.
  Material get(const std::string& name) const;

  // A material given in a scene or graph file: a preset name (a string) or an
  // inline preset map {base: name, multipliers: {...}, density: ...}. Errors
  // name `file`, the line and the key. An inline material is named after its
  // base, or "inline" without one.
  Material resolve(const YAML::Node& spec, const std::string& file) const;

  std::vector<std::string> names() const;  // sorted
  bool contains(const std::string& name) const { return presets_.count(name) != 0; }
  const MaterialPreset& preset(const std::string& name) const;  // ConfigError when unknown

  // Resolves every preset; throws the first error. load() cannot do this by
  // itself when a file builds on presets of another one.
  void check() const;

 private:
  Material resolve_preset(const MaterialPreset& preset, std::vector<std::string>& chain) const;
  std::map<std::string, MaterialPreset> presets_;
};

// Parses one preset body: the map under a preset name, or an inline map (name
// empty). `where` locates the preset in errors that concern it as a whole.
MaterialPreset parse_material_preset(const std::string& name, const YAML::Node& body, const std::string& file,
                                     const SourceLocation& where);

// The text of graphs/materials/presets.yaml as it was at build time.
const std::string& builtin_material_presets_yaml();

}  // namespace drape
