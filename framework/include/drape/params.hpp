#pragma once
// Typed node parameters read from YAML, with defaults, docs and range checks.
// Every value remembers the file and line it came from so that a bad value is
// reported where the user wrote it, even after a `base:` graph was merged in.
#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drape {

enum class ParamType { Int, Float, Bool, String, IntList, FloatList };
const char* to_string(ParamType type);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Float;
  std::string default_value;  // YAML text, e.g. "64", "[32, 64]", "relu"
  std::string doc;
  std::optional<double> min{};  // inclusive bounds, applied to every element of lists
  std::optional<double> max{};
  std::vector<std::string> choices{};  // allowed values of a String parameter (empty: any)
  // A garment's parameter that fits it to another body than the one a drape
  // starts from when set off its default (a MakeHuman outfit's body
  // sliders): a start that fails names it, with the default to keep (ABI 11).
  bool fits_start_body = false;
};

// A raw YAML value and where it was written.
struct ParamValue {
  YAML::Node node;
  SourceLocation where;
};
using ParamValues = std::map<std::string, ParamValue>;

// The entries of a YAML map as ParamValues (node must be a map or null).
ParamValues param_values_from_yaml(const YAML::Node& map, const std::string& file);

class Params {
 public:
  Params() = default;
  // Validates `values` against `specs`: unknown keys (with close matches), type
  // errors and range violations throw ConfigError naming `owner` and the location.
  Params(const std::vector<ParamSpec>& specs, const ParamValues& values, const std::string& owner);

  long get_int(const std::string& name) const;
  double get_float(const std::string& name) const;
  bool get_bool(const std::string& name) const;
  std::string get_string(const std::string& name) const;
  std::vector<long> get_int_list(const std::string& name) const;
  std::vector<double> get_float_list(const std::string& name) const;

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  // The resolved values (defaults filled in) as a YAML map, for checkpoints and printing.
  YAML::Node to_yaml() const;

 private:
  const YAML::Node& value(const std::string& name, ParamType expected) const;
  std::map<std::string, std::pair<ParamType, YAML::Node>> values_;
};

}  // namespace drape
