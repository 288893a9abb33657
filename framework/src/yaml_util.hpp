#pragma once
// Helpers every YAML reader of the framework shares (graphs, scenes, material
// presets): where a node was written, single values, key checks with close
// matches, and loading text or files with malformed YAML reported at its line.
#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace drape::yaml {

// file:line of a node (line 0 when the node is absent).
SourceLocation at(const std::string& file, const YAML::Node& n);

// "a, b, c".
std::string joined(const std::vector<std::string>& items, const std::string& separator = ", ");

// The node's text; ConfigError "<what> must be a single value" at its line otherwise.
std::string scalar(const std::string& file, const YAML::Node& n, const std::string& what);

// ConfigError at the first key not in `allowed` ("<owner>: unknown key 'x'; did
// you mean ... (allowed: ...)"), or when `map` is not a map.
void check_keys(const std::string& file, const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& owner);

// A drape file of another kind than `expected` ("graph", "scene",
// "experiment") given where that kind is read: ConfigError at line 1 naming
// the kind its top-level keys are, and the command that reads it (an
// experiment given to graph check was "unknown key 'name'; did you mean
// 'base'?"). Nothing when the file has a key of its own kind.
void check_file_kind(const std::string& file, const YAML::Node& root, const std::string& expected);

// Parse YAML; ConfigError "malformed YAML" at file:line on a syntax error, at
// the second's line for a key given twice in one map (yaml-cpp would keep one
// silently), and for load_file also when the file cannot be read.
YAML::Node load_text(const std::string& text, const std::string& name_for_errors);
YAML::Node load_file(const std::filesystem::path& path);

}  // namespace drape::yaml
