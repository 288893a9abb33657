#pragma once
// Named cloth materials read from YAML (format: docs/materials.md). The presets
// shipped in graphs/materials/presets.yaml are compiled into the library
// (MaterialTable::builtin()); users add or replace presets with their own file:
//
//   MaterialTable table = MaterialTable::builtin();
//   table.merge(MaterialTable::load("my_materials.yaml"));
//   Material knit = table.get("gray-interlock");
//
// A preset either sets every physical field, reads an ArcSim material file
// (`file:`), or names a `base:` preset and scales (`multipliers:`) or replaces
// fields of it. Two models: `linear` (stretch [4], bending scalar) and `arcsim`
// (ArcSim's measured tables: stretching 6x4, bending 3x5). Bases are looked up when a
// preset is resolved (get/resolve), in the table as it is then, so a preset of
// one file may build on a preset of another and a merged file may replace a base
// for everything built on it.
#include <drape/energy.hpp>
#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <array>
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

  // The model its fields belong to: `model:` when given, else inferred from
  // the fields (`stretching`, a table `bending` or `file` -> arcsim; `stretch`
  // or a number `bending` -> linear). Empty only for a preset with a base that
  // sets no model-specific field: it takes its base's model.
  std::optional<Material::Model> model;
  // The ArcSim file the data came from (as named, relative to the naming
  // file's folder resolved), empty when none. Its density, stretching and
  // bending (with the preset's multipliers already applied) are in the fields below.
  std::string file;

  // Fields the preset sets, each with where it was written.
  std::optional<double> density, thickness;
  std::optional<double> bending;                  // linear
  std::optional<Eigen::Vector4d> stretch;         // linear
  std::optional<std::array<Eigen::Vector4d, 6>> stretching;               // arcsim
  std::optional<std::array<std::array<double, 5>, 3>> bending_table;     // arcsim (the `bending` key)
  std::map<std::string, SourceLocation> field_where;  // "density", "stretch", ...

  // Factors applied to the base's values (1 when not given; only with a base
  // or a file: a file's data come already scaled and these are then 1).
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

  // A material given in a scene or graph file: a preset name (a string), the
  // path of an ArcSim material file (a string ending in `.json`, relative to
  // `file`'s folder) or an inline preset map {base: name, multipliers: {...},
  // density: ...} or {file: x.json, ...}. Errors name `file`, the line and the
  // key. An inline material is named after its base, its file's stem, or
  // "inline" without either.
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

// Reads an ArcSim material file (materials/*.json: density, stretching 6x4,
// bending 3x5; `//` comments allowed) as a model-arcsim material named after
// the file's stem, thickness 4.7e-4 m unless the file sets one. ConfigError
// naming the file, line and field for anything ArcSim's data must not be.
Material load_arcsim_material(const std::filesystem::path& path);

// `spec` (a material as a scene names it, see MaterialTable::resolve) with
// every ArcSim file it names replaced by the file's resolved data inline
// (model: arcsim, density, stretching, bending, thickness): the same material
// read from anywhere, which is what a serialised scene must store. A spec
// without a file comes back unchanged. `file` is where the spec was written.
YAML::Node self_contained_material_spec(const YAML::Node& spec, const std::string& file);

// The text of graphs/materials/presets.yaml as it was at build time.
const std::string& builtin_material_presets_yaml();

}  // namespace drape
