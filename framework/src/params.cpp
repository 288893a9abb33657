#include <drape/params.hpp>
#include <drape/param_range.hpp>

#include <cmath>
#include <sstream>

namespace drape {

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::Int: return "int";
    case ParamType::Float: return "float";
    case ParamType::Bool: return "bool";
    case ParamType::String: return "string";
    case ParamType::IntList: return "list of int";
    case ParamType::FloatList: return "list of float";
  }
  return "?";
}

ParamValues param_values_from_yaml(const YAML::Node& map, const std::string& file) {
  ParamValues out;
  if (!map || map.IsNull()) return out;
  if (!map.IsMap()) throw ConfigError({file, map.Mark().line + 1}, "`params` must be a map of name: value");
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    out[key] = ParamValue{kv.second, {file, kv.first.Mark().line + 1}};
  }
  return out;
}

std::string range_text(const ParamSpec& s) {
  std::ostringstream o;
  // Numbers as written in a scene (0.5, 1e+06), not std::to_string's six decimals (0.500000).
  o.precision(10);
  o << "[";
  if (s.min) o << *s.min; else o << "-inf";
  o << ", ";
  if (s.max) o << *s.max; else o << "inf";
  o << "]";
  return o.str();
}

namespace {

// Converts and range-checks one scalar; throws a message without location.
double scalar(const YAML::Node& n, bool integral) {
  if (!n.IsScalar()) throw std::invalid_argument("expected a number");
  const std::string text = n.Scalar();
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    throw std::invalid_argument("'" + text + "' is not a number");
  }
  if (used != text.size()) throw std::invalid_argument("'" + text + "' is not a number");
  if (!std::isfinite(v)) throw std::invalid_argument("'" + text + "' is not finite");
  if (integral && v != std::floor(v)) throw std::invalid_argument("'" + text + "' is not an integer");
  return v;
}


void check_range(const ParamSpec& s, double v) {
  if ((s.min && v < *s.min) || (s.max && v > *s.max)) {
    std::ostringstream o;
    o << v << " is outside the allowed range " << range_text(s);
    throw std::invalid_argument(o.str());
  }
}

// Validates `n` against the spec and returns it normalised (lists stay lists).
YAML::Node validate(const ParamSpec& s, const YAML::Node& n) {
  switch (s.type) {
    case ParamType::Int:
    case ParamType::Float: {
      check_range(s, scalar(n, s.type == ParamType::Int));
      return n;
    }
    case ParamType::Bool: {
      bool b = false;
      if (!n.IsScalar() || !YAML::convert<bool>::decode(n, b)) throw std::invalid_argument("expected true or false");
      return n;
    }
    case ParamType::String: {
      if (!n.IsScalar()) throw std::invalid_argument("expected a string");
      if (!s.choices.empty()) {
        for (const auto& c : s.choices)
          if (c == n.Scalar()) return n;
        std::string list;
        for (const auto& c : s.choices) list += (list.empty() ? "" : ", ") + c;
        throw std::invalid_argument("'" + n.Scalar() + "' is not one of: " + list + did_you_mean(n.Scalar(), s.choices));
      }
      return n;
    }
    case ParamType::IntList:
    case ParamType::FloatList: {
      // A single value is a list of one. (A fresh node: assigning to a yaml-cpp
      // node that aliases `n` would overwrite the user's value in place.)
      YAML::Node list(YAML::NodeType::Sequence);
      if (n.IsScalar()) list.push_back(YAML::Clone(n));
      else if (n.IsSequence()) list = YAML::Clone(n);
      else throw std::invalid_argument("expected a list");
      for (const auto& e : list) check_range(s, scalar(e, s.type == ParamType::IntList));
      return list;
    }
  }
  return n;
}

}  // namespace

Params::Params(const std::vector<ParamSpec>& specs, const ParamValues& values, const std::string& owner) {
  std::vector<std::string> known;
  for (const auto& s : specs) known.push_back(s.name);
  for (const auto& [key, v] : values) {
    bool found = false;
    for (const auto& s : specs) found = found || s.name == key;
    if (!found) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw ConfigError(v.where, owner + ": unknown parameter '" + key + "'" + did_you_mean(key, known) +
                                     (list.empty() ? " (it takes no parameters)" : " (known: " + list + ")"));
    }
  }
  for (const auto& s : specs) {
    auto it = values.find(s.name);
    YAML::Node raw;
    SourceLocation where{"<default>", 0};
    if (it != values.end()) {
      raw = it->second.node;
      where = it->second.where;
    } else {
      raw = YAML::Load(s.default_value);
    }
    try {
      values_[s.name] = {s.type, validate(s, raw)};
    } catch (const std::invalid_argument& e) {
      throw ConfigError(where, owner + ": parameter '" + s.name + "' (" + to_string(s.type) + "): " + e.what());
    }
  }
}

const YAML::Node& Params::value(const std::string& name, ParamType expected) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw Error("internal: parameter '" + name + "' was not declared by the plugin");
  const bool compatible = it->second.first == expected ||
                          (expected == ParamType::Float && it->second.first == ParamType::Int) ||
                          (expected == ParamType::FloatList && it->second.first == ParamType::IntList);
  if (!compatible)
    throw Error("internal: parameter '" + name + "' is declared " + to_string(it->second.first) + ", read as " +
                to_string(expected));
  return it->second.second;
}

long Params::get_int(const std::string& name) const { return std::lround(scalar(value(name, ParamType::Int), true)); }
double Params::get_float(const std::string& name) const { return scalar(value(name, ParamType::Float), false); }
bool Params::get_bool(const std::string& name) const { return value(name, ParamType::Bool).as<bool>(); }
std::string Params::get_string(const std::string& name) const {
  return value(name, ParamType::String).Scalar();
}
std::vector<long> Params::get_int_list(const std::string& name) const {
  std::vector<long> out;
  for (const auto& e : value(name, ParamType::IntList)) out.push_back(std::lround(scalar(e, true)));
  return out;
}
std::vector<double> Params::get_float_list(const std::string& name) const {
  std::vector<double> out;
  for (const auto& e : value(name, ParamType::FloatList)) out.push_back(scalar(e, false));
  return out;
}

YAML::Node Params::to_yaml() const {
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& [k, v] : values_) out[k] = YAML::Clone(v.second);
  return out;
}

}  // namespace drape
