// Parsing one material preset: keys, types and value ranges, each error at the
// file:line of the key or value at fault.
#include <drape/materials.hpp>

#include "material_validation.hpp"
#include "../yaml_util.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape {
namespace materials_detail {

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

}  // namespace materials_detail

namespace {

using materials_detail::check_stretch;

using yaml::at;


using yaml::check_keys;

double number(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key) {
  if (!n.IsScalar())
    throw ConfigError(at(file, n), owner + ": `" + key + "` must be a number, got " + (n.IsSequence() ? "a list" : "a map"));
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(at(file, n), owner + ": `" + key + "` must be a number, got '" + n.Scalar() + "'");
  }
  if (!std::isfinite(v)) throw ConfigError(at(file, n), owner + ": `" + key + "` must be a finite number, got " + n.Scalar());
  return v;
}

double positive(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key,
                const char* unit) {
  const double v = number(file, n, owner, key);
  if (v <= 0) {
    std::ostringstream s;
    s << owner << ": `" << key << "` must be > 0 " << unit << ", got " << v;
    throw ConfigError(at(file, n), s.str());
  }
  return v;
}

Eigen::Vector4d stretch_of(const std::string& file, const YAML::Node& n, const std::string& owner) {
  if (!n.IsSequence() || n.size() != 4)
    throw ConfigError(at(file, n), owner + ": `stretch` must be a list of 4 numbers [k_uu, k_uv, k_vv, k_shear] in N/m" +
                                       (n.IsSequence() ? ", got " + std::to_string(n.size()) : std::string()));
  Eigen::Vector4d k;
  for (int i = 0; i < 4; ++i) k[i] = number(file, n[i], owner, "stretch");
  check_stretch(k, at(file, n), owner);
  return k;
}

}  // namespace

MaterialPreset parse_material_preset(const std::string& name, const YAML::Node& body, const std::string& file,
                                     const SourceLocation& where) {
  MaterialPreset p;
  p.name = name;
  p.where = where;
  const std::string owner = name.empty() ? std::string("inline material") : "material '" + name + "'";
  if (!body.IsMap())
    throw ConfigError(p.where, owner + " must be a map of density, stretch, bending, thickness (or base and multipliers)");
  check_keys(file, body, {"doc", "base", "multipliers", "density", "stretch", "bending", "thickness"}, owner);

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
    } else if (key == "thickness") {
      p.thickness = positive(file, value, owner, key, "m");
    } else if (key == "bending") {
      const double b = number(file, value, owner, key);
      if (b < 0) throw ConfigError(at(file, value), owner + ": `bending` must be >= 0 N*m, got " + value.Scalar());
      p.bending = b;
    } else if (key == "stretch") {
      p.stretch = stretch_of(file, value, owner);
    }
  }

  if (const YAML::Node m = body["multipliers"]) {
    const SourceLocation where = p.field_where["multipliers"];
    if (p.base.empty())
      throw ConfigError(where, owner + ": `multipliers` scale a base material; add `base: <name>`");
    if (!m.IsMap()) throw ConfigError(at(file, m), owner + ": `multipliers` must be a map such as {stretch: 5, bend: 10}");
    check_keys(file, m, {"stretch", "bend", "density", "thickness"}, owner + " multipliers");
    // A field both set and scaled would be ambiguous (scale the base or the new value?).
    const std::map<std::string, std::string> field_of{
        {"stretch", "stretch"}, {"bend", "bending"}, {"density", "density"}, {"thickness", "thickness"}};
    for (const auto& kv : m) {
      const std::string key = kv.first.as<std::string>();
      const double factor = positive(file, kv.second, owner, "multipliers." + key, "(a factor)");
      if (body[field_of.at(key)])
        throw ConfigError(at(file, kv.first), owner + ": `multipliers." + key + "` and `" + field_of.at(key) +
                                                  "` both given; set the value or scale the base's, not both");
      if (key == "stretch") p.stretch_multiplier = factor;
      if (key == "bend") p.bend_multiplier = factor;
      if (key == "density") p.density_multiplier = factor;
      if (key == "thickness") p.thickness_multiplier = factor;
    }
  }

  if (p.base.empty()) {
    std::vector<std::string> missing;
    if (!p.density) missing.push_back("density");
    if (!p.stretch) missing.push_back("stretch");
    if (!p.bending) missing.push_back("bending");
    if (!p.thickness) missing.push_back("thickness");
    if (!missing.empty())
      throw ConfigError(p.where, owner + " has no `base`, so it must set density, stretch, bending and thickness; missing: " +
                                     yaml::joined(missing));
  }
  return p;
}

}  // namespace drape
