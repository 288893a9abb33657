// MaterialTable: preset files, merging, and resolving presets through their
// `base:` chains (multipliers on the base's values, then the preset's own fields).
#include <drape/materials/materials.hpp>

#include "material_validation.hpp"
#include "../yaml_util.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace drape {
namespace {

using yaml::at;
using yaml::joined;
using Model = Material::Model;

std::string owner_of(const MaterialPreset& p) { return materials_detail::owner_of(p.name); }

const char* table_model_name(Model m) { return m == Model::Arcsim ? "arcsim" : "linear"; }

// Where the preset's fields are checked again after resolution: the field
// itself when the preset sets it, else the preset.
SourceLocation where_of(const MaterialPreset& p, const std::string& field) {
  const auto it = p.field_where.find(field);
  return it != p.field_where.end() ? it->second : p.where;
}

// The value the simulator will use must be valid whatever chain produced it
// (positive factors keep valid values valid; checked anyway).
void check_resolved(const Material& m, const MaterialPreset& p) {
  // A density no cloth has (set, or a base's scaled): the solver's measures
  // of balance divide by the cloth's weight, and an outside check's 1e-30
  // kg/m^2 shirt was torn apart (edges 17 times their length) and reported
  // settled, its weight below the floor the solver keeps for a weightless
  // cloth.
  if (!(m.density >= materials_detail::kMinDensity)) {
    std::ostringstream s;
    s << owner_of(p) << ": its density is " << m.density << " kg/m^2, below any cloth drape simulates (at least "
      << materials_detail::kMinDensity << " kg/m^2; chiffon, among the lightest fabrics, is about 0.02, ArcSim's "
      << "materials 0.07-0.32): a unit mistake, or a multiplier too small?";
    throw ConfigError(where_of(p, p.density ? "density" : "multipliers"), s.str());
  }
  if (m.model == Model::Linear)
    materials_detail::check_stretch(m.stretch, where_of(p, "stretch"), owner_of(p));
  else
    materials_detail::check_zero_strain_row(m.arcsim.stretching[0], where_of(p, "stretching"), owner_of(p));
}

std::string name_of(const MaterialPreset& p) {
  if (!p.name.empty()) return p.name;
  if (!p.base.empty()) return p.base;
  if (!p.file.empty()) return std::filesystem::path(p.file).stem().string();
  return "inline";
}

}  // namespace

namespace materials_detail {

Material complete_material(const MaterialPreset& p) {
  // parse_material_preset guarantees the model's fields without a base.
  Material m;
  m.model = *p.model;
  m.density = *p.density;
  m.thickness = *p.thickness;
  if (m.model == Model::Linear) {
    m.stretch = *p.stretch;
    m.bending = *p.bending;
  } else {
    m.arcsim.stretching = *p.stretching;
    m.arcsim.bending = *p.bending_table;
  }
  check_resolved(m, p);
  m.name = name_of(p);
  return m;
}

}  // namespace materials_detail

MaterialTable MaterialTable::parse(const std::string& yaml_text, const std::string& file) {
  const YAML::Node root = yaml::load_text(yaml_text, file);
  MaterialTable table;
  if (!root || root.IsNull()) return table;  // an empty file: no presets
  if (!root.IsMap())
    throw ConfigError({file, 1}, "a material file must be a map of name: {density, stretch, bending, thickness} "
                                 "or name: {base, multipliers, ...}");
  for (const auto& kv : root) {
    const SourceLocation where = at(file, kv.first);
    if (!kv.first.IsScalar() || kv.first.Scalar().empty())
      throw ConfigError(where, "a material name must be a non-empty string");
    const std::string name = kv.first.Scalar();
    if (const auto it = table.presets_.find(name); it != table.presets_.end())
      throw ConfigError(where, "material '" + name + "' is defined twice (first at line " +
                                   std::to_string(it->second.where.line) + ")");
    table.presets_.emplace(name, parse_material_preset(name, kv.second, file, where));
  }
  return table;
}

MaterialTable MaterialTable::load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(SourceLocation{path.string(), 0}, std::string("cannot read material file: ") + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path.string());
}

MaterialTable MaterialTable::builtin() {
  // Parsed and checked once; a broken shipped file is a build defect that the
  // tests catch, so every call reporting it again is fine.
  static const MaterialTable table = [] {
    MaterialTable t = parse(builtin_material_presets_yaml(), "graphs/materials/presets.yaml");
    t.check();
    return t;
  }();
  return table;
}

void MaterialTable::merge(const MaterialTable& other) {
  for (const auto& [name, preset] : other.presets_) presets_.insert_or_assign(name, preset);
}

std::vector<std::string> MaterialTable::names() const {
  std::vector<std::string> out;
  for (const auto& kv : presets_) out.push_back(kv.first);
  return out;
}

const MaterialPreset& MaterialTable::preset(const std::string& name) const {
  const auto it = presets_.find(name);
  if (it == presets_.end())
    throw ConfigError("unknown material '" + name + "'" + did_you_mean(name, names()) + " (known: " + joined(names(), ", ") + ")");
  return it->second;
}

Material MaterialTable::get(const std::string& name) const {
  std::vector<std::string> chain;
  return resolve_preset(preset(name), chain);
}

Material MaterialTable::resolve_preset(const MaterialPreset& p, std::vector<std::string>& chain) const {
  if (p.base.empty()) return materials_detail::complete_material(p);
  const std::string owner = owner_of(p);
  chain.push_back(p.name);
  if (const auto loop = std::find(chain.begin(), chain.end(), p.base); loop != chain.end()) {
    const std::vector<std::string> cycle(loop, chain.end());
    throw ConfigError(p.base_where, owner + ": `base` makes a cycle: " + joined(cycle, " -> ") + " -> " + p.base);
  }
  const auto it = presets_.find(p.base);
  if (it == presets_.end()) {
    std::vector<std::string> others = names();  // a preset cannot be its own base: don't suggest it
    others.erase(std::remove(others.begin(), others.end(), p.name), others.end());
    throw ConfigError(p.base_where, owner + ": unknown `base` '" + p.base + "'" + did_you_mean(p.base, others) +
                                        " (known: " + joined(others, ", ") + ")");
  }
  Material m = resolve_preset(it->second, chain);
  chain.pop_back();
  // The preset's fields are of one model; a base of the other has no such fields.
  if (p.model && *p.model != m.model)
    throw ConfigError(where_of(p, "model"), owner + " is model " + table_model_name(*p.model) + " but its base '" + p.base +
                                                "' is model " + table_model_name(m.model) +
                                                "; a preset keeps its base's model");
  m.density *= p.density_multiplier;
  m.thickness *= p.thickness_multiplier;
  if (p.density) m.density = *p.density;
  if (p.thickness) m.thickness = *p.thickness;
  if (m.model == Model::Linear) {
    m.stretch *= p.stretch_multiplier;
    m.bending *= p.bend_multiplier;
    if (p.stretch) m.stretch = *p.stretch;
    if (p.bending) m.bending = *p.bending;
  } else {
    // As ArcSim's stretching_mult and bending_mult: every sample of the tables.
    for (Eigen::Vector4d& row : m.arcsim.stretching) row *= p.stretch_multiplier;
    for (auto& row : m.arcsim.bending)
      for (double& b : row) b *= p.bend_multiplier;
    if (p.stretching) m.arcsim.stretching = *p.stretching;
    if (p.bending_table) m.arcsim.bending = *p.bending_table;
  }
  check_resolved(m, p);
  m.name = name_of(p);
  return m;
}

Material MaterialTable::resolve(const YAML::Node& spec, const std::string& file) const {
  const SourceLocation where = at(file, spec);
  if (spec && spec.IsScalar() && materials_detail::names_arcsim_file(spec.Scalar())) {
    const std::filesystem::path path = materials_detail::relative_to(file, spec.Scalar());
    return materials_detail::complete_material(materials_detail::read_arcsim_file(path, path.stem().string(), where));
  }
  if (spec && spec.IsScalar()) {
    const std::string name = spec.Scalar();
    if (!contains(name))
      throw ConfigError(where, "unknown material '" + name + "'" + did_you_mean(name, names()) + " (known: " +
                                   joined(names(), ", ") + ")");
    return get(name);
  }
  if (spec && spec.IsMap()) {
    const MaterialPreset inline_preset = parse_material_preset("", spec, file, where);
    std::vector<std::string> chain;
    return resolve_preset(inline_preset, chain);
  }
  throw ConfigError(where, "a material must be a preset name (one of " + joined(names(), ", ") +
                               "), the path of an ArcSim material file (x.json) or a map such as "
                               "{base: gray-interlock, multipliers: {stretch: 2}}");
}

void MaterialTable::check() const {
  for (const auto& kv : presets_) get(kv.first);
}

}  // namespace drape
