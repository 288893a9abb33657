// Parsing one material preset: keys, the model, types and value ranges, each
// error at the file:line of the key or value at fault. The preset's `file:`
// (an ArcSim material file) is read here too, so that a bad file fails when
// the preset is parsed.
#include <drape/materials/materials.hpp>

#include "material_validation.hpp"
#include "../yaml_util.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape {
namespace materials_detail {

std::string owner_of(const std::string& preset_name) {
  return preset_name.empty() ? std::string("inline material") : "material '" + preset_name + "'";
}

void check_stretch(const Eigen::Vector4d& k, const SourceLocation& where, const std::string& owner) {
  const auto fail = [&](const std::string& why) {
    std::ostringstream s;
    s << owner << ": `stretch` [k_uu, k_uv, k_vv, k_shear] = [" << k[0] << ", " << k[1] << ", " << k[2] << ", " << k[3]
      << "] " << why;
    throw ConfigError(where, s.str());
  };
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(k[i])) fail("has a value that is not a finite number");
  if (k[0] <= 0 || k[2] <= 0) fail("needs k_uu > 0 and k_vv > 0 (stiffness against stretching)");
  if (k[3] <= 0) fail("needs k_shear > 0 (stiffness against shearing)");
  const double det = k[0] * k[2] - k[1] * k[1];
  if (det <= 0) {
    std::ostringstream why;
    why << "is not positive definite: k_uu k_vv - k_uv^2 = " << det
        << " <= 0, so stretching along u and v together would have negative or zero energy (|k_uv| must be below "
        << std::sqrt(k[0] * k[2]) << ")";
    fail(why.str());
  }
}

double number(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key) {
  if (!n.IsScalar())
    throw ConfigError(yaml::at(file, n), owner + ": `" + key + "` must be a number, got " +
                                             (n.IsSequence() ? "a list" : n.IsMap() ? "a map" : "nothing"));
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(yaml::at(file, n), owner + ": `" + key + "` must be a number, got '" + n.Scalar() + "'");
  }
  // A quoted number is text, in JSON as in YAML: "0.187" was read as the
  // number (an outside check), where the docs ask for numbers.
  if (n.Tag() == "!")
    throw ConfigError(yaml::at(file, n), owner + ": `" + key + "` must be a number, got the text \"" + n.Scalar() +
                                             "\" (write it without quotes)");
  if (!std::isfinite(v))
    throw ConfigError(yaml::at(file, n), owner + ": `" + key + "` must be a finite number, got " + n.Scalar());
  return v;
}

void check_cloth_range(double v, double limit, const std::string& file, const YAML::Node& n, const std::string& owner,
                       const std::string& key, const char* unit) {
  if (std::abs(v) <= limit) return;
  std::ostringstream s;
  s << owner << ": `" << key << "` is " << v << " " << unit << ", beyond any cloth or sheet drape simulates (at most "
    << limit << " " << unit << "; ArcSim's measured materials are far below): a typo or a unit mistake?";
  throw ConfigError(yaml::at(file, n), s.str());
}

double positive(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key,
                const char* unit) {
  const double v = number(file, n, owner, key);
  if (v <= 0) {
    std::ostringstream s;
    s << owner << ": `" << key << "` must be > 0 " << unit << ", got " << v;
    throw ConfigError(yaml::at(file, n), s.str());
  }
  return v;
}

}  // namespace materials_detail

namespace {

using namespace materials_detail;
using yaml::at;
using yaml::check_keys;

const std::vector<std::string> kPresetKeys{"doc",     "model",   "file",    "base",      "multipliers",
                                           "density", "stretch", "bending", "stretching", "thickness"};
// What an ArcSim file may hold: a complete material, no references to others.
const std::vector<std::string> kFileKeys{"doc", "model", "density", "stretching", "bending", "thickness"};

const char* model_name(Material::Model m) { return m == Material::Model::Arcsim ? "arcsim" : "linear"; }

// The model the preset's fields belong to (see MaterialPreset::model), and
// where that was decided (p.field_where["model"]).
std::optional<Material::Model> model_of(const YAML::Node& body, const std::string& file, const std::string& owner,
                                        MaterialPreset& p) {
  using M = Material::Model;
  if (const YAML::Node m = body["model"]) {
    const std::string name = m.IsScalar() ? m.Scalar() : std::string();
    if (name == "linear") return M::Linear;
    if (name == "arcsim") return M::Arcsim;
    throw ConfigError(at(file, m), owner + ": `model` must be linear or arcsim, got " +
                                       (name.empty() ? std::string("a list or map") : "'" + name + "'") +
                                       did_you_mean(name, {"linear", "arcsim"}));
  }
  // Inferred from the first field that belongs to one model only.
  for (const auto& kv : body) {
    const std::string key = kv.first.as<std::string>();
    std::optional<M> decided;
    if (key == "file" || key == "stretching") decided = M::Arcsim;
    if (key == "stretch") decided = M::Linear;
    if (key == "bending") decided = kv.second.IsSequence() ? M::Arcsim : M::Linear;
    if (decided) {
      p.field_where["model"] = at(file, kv.first);
      return decided;
    }
  }
  if (!body["base"]) return M::Linear;  // reported below as a linear preset missing its fields
  return std::nullopt;
}

// Where `key` is written in `body` (its key, not its value).
SourceLocation key_at(const std::string& file, const YAML::Node& body, const std::string& key) {
  for (const auto& kv : body)
    if (kv.first.as<std::string>() == key) return at(file, kv.first);
  return at(file, body);
}

// A field of the other model: say what this model has instead.
void check_model_fields(const YAML::Node& body, const std::string& file, const std::string& owner, Material::Model model) {
  const bool arcsim = model == Material::Model::Arcsim;
  const char* foreign = arcsim ? "stretch" : "stretching";
  if (body[foreign])
    throw ConfigError(key_at(file, body, foreign),
                      owner + ": `" + foreign + "` is a field of model " + (arcsim ? "linear" : "arcsim") +
                          ", and this material is model " + model_name(model) +
                          (arcsim ? " (it has `stretching`: 6 rows of 4, and `bending`: 3 rows of 5)"
                                  : " (it has `stretch`: 4 numbers, and `bending`: one number)"));
}

// With `file:`, the file is the whole material: fields it sets cannot be
// given beside it (doc, thickness and multipliers can).
void check_file_fields(const YAML::Node& body, const std::string& file, const std::string& owner) {
  for (const char* key : {"base", "density", "stretching", "bending"})
    if (body[key])
      throw ConfigError(key_at(file, body, key), owner + ": `" + key + "` and `file` both given; the file is the whole " +
                                                     "material (scale its values with `multipliers`)");
}

void parse_fields(const YAML::Node& body, const std::string& file, const std::string& owner, MaterialPreset& p) {
  for (const auto& kv : body) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& value = kv.second;
    p.field_where[key] = at(file, kv.first);
    if (key == "doc") {
      if (!value.IsScalar()) throw ConfigError(at(file, value), owner + ": `doc` must be text");
      p.doc = value.Scalar();
    } else if (key == "base") {
      if (!value.IsScalar() || value.Scalar().empty())
        throw ConfigError(at(file, value), owner + ": `base` must be the name of another material");
      p.base = value.Scalar();
      p.base_where = at(file, value);
    } else if (key == "density") {
      p.density = positive(file, value, owner, key, "kg/m^2");
      check_cloth_range(*p.density, kMaxDensity, file, value, owner, key, "kg/m^2");
    } else if (key == "thickness") {
      p.thickness = positive(file, value, owner, key, "m");
    } else if (key == "bending" && p.model == Material::Model::Arcsim) {
      p.bending_table = bending_table(file, value, owner);
    } else if (key == "bending") {
      const double b = number(file, value, owner, key);
      if (b < 0) throw ConfigError(at(file, value), owner + ": `bending` must be >= 0 N*m, got " + value.Scalar());
      check_cloth_range(b, kMaxBending, file, value, owner, key, "N*m");
      p.bending = b;
    } else if (key == "stretch") {
      if (!value.IsSequence() || value.size() != 4)
        throw ConfigError(at(file, value), owner + ": `stretch` must be a list of 4 numbers [k_uu, k_uv, k_vv, k_shear] in N/m" +
                                               (value.IsSequence() ? ", got " + std::to_string(value.size()) : std::string()));
      Eigen::Vector4d k;
      for (int i = 0; i < 4; ++i) {
        k[i] = number(file, value[i], owner, "stretch");
        check_cloth_range(k[i], kMaxStretch, file, value[i], owner, "stretch[" + std::to_string(i) + "]", "N/m");
      }
      check_stretch(k, at(file, value), owner);
      p.stretch = k;
    } else if (key == "stretching") {
      p.stretching = stretching_table(file, value, owner);
    }
  }
}

// `file:`: the ArcSim file's data become the preset's; it may add doc,
// thickness and multipliers, nothing else (the file is the whole material).
void read_file_field(const YAML::Node& body, const std::string& file, const std::string& owner, MaterialPreset& p) {
  const YAML::Node f = body["file"];
  if (!f.IsScalar() || f.Scalar().empty())
    throw ConfigError(at(file, f), owner + ": `file` must be the path of an ArcSim material file (.json)");
  const std::filesystem::path path = relative_to(file, f.Scalar());
  const MaterialPreset data = read_arcsim_file(path, path.stem().string(), at(file, f));
  p.file = path.string();
  p.density = data.density;
  p.stretching = data.stretching;
  p.bending_table = data.bending_table;
  if (!p.thickness) p.thickness = data.thickness;
  if (p.doc.empty()) p.doc = data.doc;
}

void parse_multipliers(const YAML::Node& body, const std::string& file, const std::string& owner, MaterialPreset& p) {
  const YAML::Node m = body["multipliers"];
  if (!m) return;
  const SourceLocation where = p.field_where["multipliers"];
  if (p.base.empty() && p.file.empty())
    throw ConfigError(where, owner + ": `multipliers` scale a base material; add `base: <name>` (or `file: <x.json>`)");
  if (!m.IsMap()) throw ConfigError(at(file, m), owner + ": `multipliers` must be a map such as {stretch: 5, bend: 10}");
  check_keys(file, m, {"stretch", "bend", "density", "thickness"}, owner + " multipliers");
  // A field both set and scaled would be ambiguous (scale the base or the new value?).
  const bool arcsim = p.model == Material::Model::Arcsim;
  const std::map<std::string, std::string> field_of{{"stretch", arcsim ? "stretching" : "stretch"},
                                                    {"bend", "bending"},
                                                    {"density", "density"},
                                                    {"thickness", "thickness"}};
  for (const auto& kv : m) {
    const std::string key = kv.first.as<std::string>();
    const double factor = positive(file, kv.second, owner, "multipliers." + key, "(a factor)");
    check_cloth_range(factor, kMaxMultiplier, file, kv.second, owner, "multipliers." + key, "(a factor)");
    if (body[field_of.at(key)])
      throw ConfigError(at(file, kv.first), owner + ": `multipliers." + key + "` and `" + field_of.at(key) +
                                                "` both given; set the value or scale the base's, not both");
    if (key == "stretch") p.stretch_multiplier = factor;
    if (key == "bend") p.bend_multiplier = factor;
    if (key == "density") p.density_multiplier = factor;
    if (key == "thickness") p.thickness_multiplier = factor;
  }
  if (!p.file.empty()) {
    // The file is the base: scale its data now, as ArcSim's stretching_mult
    // and bending_mult scale every sample of the table.
    for (Eigen::Vector4d& row : *p.stretching) row *= p.stretch_multiplier;
    for (auto& row : *p.bending_table)
      for (double& b : row) b *= p.bend_multiplier;
    *p.density *= p.density_multiplier;
    *p.thickness *= p.thickness_multiplier;
    p.stretch_multiplier = p.bend_multiplier = p.density_multiplier = p.thickness_multiplier = 1;
  }
}

void check_complete(const std::string& owner, MaterialPreset& p) {
  if (!p.base.empty()) return;
  std::vector<std::string> missing;
  if (!p.density) missing.push_back("density");
  if (p.model == Material::Model::Arcsim) {
    if (!p.stretching) missing.push_back("stretching");
    if (!p.bending_table) missing.push_back("bending");
    if (!missing.empty())
      throw ConfigError(p.where, owner + ": model arcsim needs density, stretching (6x4) and bending (3x5) unless it "
                                         "has a `base`; missing: " + yaml::joined(missing));
    if (!p.thickness) p.thickness = kDefaultArcsimThickness;
    return;
  }
  if (!p.stretch) missing.push_back("stretch");
  if (!p.bending) missing.push_back("bending");
  if (!p.thickness) missing.push_back("thickness");
  if (!missing.empty())
    throw ConfigError(p.where, owner + " has no `base`, so it must set density, stretch, bending and thickness; missing: " +
                                   yaml::joined(missing));
}

MaterialPreset parse_preset(const std::string& name, const std::string& owner, const YAML::Node& body,
                            const std::string& file, const SourceLocation& where, bool is_arcsim_file) {
  MaterialPreset p;
  p.name = name;
  p.where = where;
  if (!body.IsMap())
    throw ConfigError(p.where, owner + (is_arcsim_file ? " must be a map {density, stretching, bending}"
                                                       : " must be a map of density, stretch, bending, thickness "
                                                         "(or base and multipliers, or file)"));
  check_keys(file, body, is_arcsim_file ? kFileKeys : kPresetKeys, owner);
  // An ArcSim file is model arcsim whatever fields it holds: a stray
  // `stretch` in it is reported as a linear field, not as a linear file.
  p.model = is_arcsim_file && !body["model"] ? Material::Model::Arcsim : model_of(body, file, owner, p);
  if (is_arcsim_file && p.model != Material::Model::Arcsim)
    throw ConfigError(at(file, body["model"]), owner + ": an ArcSim material file is model arcsim");
  if (p.model) check_model_fields(body, file, owner, *p.model);
  if (body["file"]) check_file_fields(body, file, owner);
  parse_fields(body, file, owner, p);
  if (body["file"]) read_file_field(body, file, owner, p);
  parse_multipliers(body, file, owner, p);
  check_complete(owner, p);
  return p;
}

}  // namespace

namespace materials_detail {

MaterialPreset parse_arcsim_file_body(const std::string& name, const YAML::Node& body, const std::string& file) {
  const std::string owner = "ArcSim material file '" + std::filesystem::path(file).filename().string() + "'";
  SourceLocation where = at(file, body);
  where.line = std::max(where.line, 1);  // an empty file has no node to point at
  return parse_preset(name, owner, body, file, where, true);
}

}  // namespace materials_detail

MaterialPreset parse_material_preset(const std::string& name, const YAML::Node& body, const std::string& file,
                                     const SourceLocation& where) {
  return parse_preset(name, owner_of(name), body, file, where, false);
}

}  // namespace drape
