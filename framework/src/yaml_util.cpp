#include "yaml_util.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace drape::yaml {

SourceLocation at(const std::string& file, const YAML::Node& n) { return {file, n ? n.Mark().line + 1 : 0}; }

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : separator) + i;
  return s;
}

std::string scalar(const std::string& file, const YAML::Node& n, const std::string& what) {
  if (!n.IsScalar()) throw ConfigError(at(file, n), what + " must be a single value");
  return n.Scalar();
}

void check_keys(const std::string& file, const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& owner) {
  if (!map.IsMap()) throw ConfigError(at(file, map), owner + " must be a map");
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      throw ConfigError(at(file, kv.first), owner + ": unknown key '" + key + "'" + did_you_mean(key, allowed) +
                                                " (allowed: " + joined(allowed) + ")");
  }
}

void check_file_kind(const std::string& file, const YAML::Node& root, const std::string& expected) {
  if (!root.IsMap()) return;
  // Each kind by the top-level keys only it has, and the command that reads it.
  struct Kind {
    const char* name;
    std::vector<std::string> keys;
    const char* read_by;
  };
  static const std::vector<Kind> kinds = {
      {"graph", {"inputs", "nodes", "outputs", "losses"}, "drape graph check, train"},
      {"scene", {"body", "garment", "materials", "effects", "solver"}, "drape simulate, generate"},
      {"experiment", {"datasets", "columns", "rows", "training"}, "drape experiment"}};
  const auto keys_of = [&](const Kind& k) {
    std::vector<std::string> found;
    for (const auto& kv : root)
      if (kv.first.IsScalar() && std::find(k.keys.begin(), k.keys.end(), kv.first.Scalar()) != k.keys.end())
        found.push_back(kv.first.Scalar());
    return found;
  };
  const auto own = std::find_if(kinds.begin(), kinds.end(), [&](const Kind& k) { return expected == k.name; });
  if (own == kinds.end() || !keys_of(*own).empty()) return;
  for (const Kind& k : kinds) {
    const std::vector<std::string> found = keys_of(k);
    if (&k == &*own || found.empty()) continue;
    throw ConfigError({file, 1}, "this is " + std::string(k.name[0] == 'e' ? "an " : "a ") + k.name + " file (its keys " +
                                     joined(found) + "), which " + k.read_by + " read; " +
                                     (own->name[0] == 'e' ? "an " : "a ") + own->name + " file has " + joined(own->keys));
  }
}

namespace {

// yaml-cpp keeps one of two equal keys of a map without a word, so a scene
// with two `garment:` entries would lose one silently; every map of a
// document is checked once, as it is loaded.
// `open` holds the nodes being walked, outermost first: an alias of a node
// inside that node itself (`a: &x [*x]`) makes the document an endless tree,
// which every reader after this one would walk until the stack overflows.
// Nodes a file may hold once its aliases are expanded: drape's files hold a
// few thousand; a 442-byte "billion laughs" (aliases nested nine deep, nine
// wide) expands to 9^9 and hung every walk of it (an outside check).
constexpr std::size_t kMostNodes = 200000;

void refuse_repeated_keys_and_cycles(const YAML::Node& node, const std::string& file, std::vector<YAML::Node>& open,
                                     std::size_t& visited) {
  if (++visited > kMostNodes)
    throw ConfigError({file, node.Mark().line + 1},
                      "more than " + std::to_string(kMostNodes) + " YAML nodes once its aliases ('*name') are expanded "
                      "(aliases of aliases?): drape's files hold a few thousand; write the file out plainly");
  if (!node.IsSequence() && !node.IsMap()) return;
  for (const YAML::Node& outer : open)
    if (outer.is(node))
      throw ConfigError({file, node.Mark().line + 1},
                        "a recursive alias: this node contains itself (an anchor '&name' used as '*name' inside the node "
                        "it names); write the repeated part out");
  open.push_back(node);
  if (node.IsSequence())
    for (const auto& item : node) refuse_repeated_keys_and_cycles(item, file, open, visited);
  if (node.IsMap()) {
    std::map<std::string, int> seen;  // key -> 1-based line
    for (const auto& kv : node) {
      if (kv.first.IsScalar()) {
        const std::string key = kv.first.Scalar();
        const int line = kv.first.Mark().line + 1;
        const auto [it, fresh] = seen.emplace(key, line);
        if (!fresh)
          throw ConfigError({file, line}, "'" + key + "' is defined twice (first at line " + std::to_string(it->second) +
                                              "); one map keeps one key once: merge the two");
      }
      refuse_repeated_keys_and_cycles(kv.first, file, open, visited);
      refuse_repeated_keys_and_cycles(kv.second, file, open, visited);
    }
  }
  open.pop_back();
}

// A bare word as the last line, at the indentation of the map entry above
// it (`morph` at the end of a file cut in the middle of `morph_steps: 20`),
// is no YAML (a key needs ':'), but yaml-cpp reads it as the key `morph`
// with no value, which a scene takes for "reset this key": the cut went
// unnoticed. Refused, naming the line.
void refuse_dangling_last_line(const std::string& text, const std::string& file) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto significant = [&](std::size_t i) {
    const auto first = lines[i].find_first_not_of(" \t\r");
    return first != std::string::npos && lines[i][first] != '#';
  };
  std::size_t last = lines.size();
  while (last > 0 && !significant(last - 1)) --last;
  if (last < 2) return;
  std::size_t above = last - 1;
  while (above > 0 && !significant(above - 1)) --above;
  if (above == 0) return;
  const std::string &line = lines[last - 1], &entry = lines[above - 1];
  const auto indent = line.find_first_not_of(" \t\r"), entry_indent = entry.find_first_not_of(" \t\r");
  if (indent != entry_indent || line.find(':') != std::string::npos ||
      std::string("-[]{}\"'|>!&*.%@`,").find(line[indent]) != std::string::npos)
    return;
  // The line above is a map entry `key: ...` (not a list item).
  if (entry[entry_indent] == '-' || entry.find(':') == std::string::npos) return;
  std::string word = line.substr(indent);
  while (!word.empty() && (word.back() == ' ' || word.back() == '\r' || word.back() == '\t')) word.pop_back();
  throw ConfigError({file, static_cast<int>(last)},
                    "'" + word + "' has no value: a key needs ':' (is the file cut short?)");
}

}  // namespace

YAML::Node load_text(const std::string& text, const std::string& name_for_errors) {
  // A binary file (a library, an HDF5 file given for a YAML one) made
  // yaml-cpp print one of its control bytes raw into the message.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw ConfigError({name_for_errors, static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n')) + 1},
                      "not a text file (a zero byte at offset " + std::to_string(nul) + "): give a YAML file");
  YAML::Node root;
  try {
    // Every document, so that a second one is refused: YAML::Load reads the
    // first and drops the rest without a word (an outside check's pose file
    // `shoulder_abduction: 60`, `---`, `elbow_flexion: 500` posed the
    // shoulders and never checked the elbows).
    const std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (!documents.empty()) root = documents.front();
    for (std::size_t d = 1; d < documents.size(); ++d)
      if (!documents[d].IsNull())
        throw ConfigError({name_for_errors, documents[d].Mark().line + 1},
                          "a second YAML document (after '---' or '...'): drape reads one document a file, and would "
                          "leave this one out; put its keys in the first");
  } catch (const YAML::Exception& e) {
    // A flow left open is found at the end of the text, which yaml-cpp
    // counts as the line after the last newline: said as the file's last line.
    int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + (text.empty() || text.back() == '\n' ? 0 : 1);
    const int line = std::min(e.mark.line + 1, std::max(lines, 1));
    // A tab in a line's indentation (YAML indents with spaces only) makes
    // yaml-cpp say "illegal map value" or "end of map not found", a line or
    // more off: the first such line at or before the error is named.
    std::string tab;
    {
      std::istringstream in(text);
      std::string row;
      for (int n = 1; std::getline(in, row) && n <= line; ++n) {
        const std::size_t indent_end = row.find_first_not_of(" \t");
        if (row.substr(0, indent_end == std::string::npos ? row.size() : indent_end).find('\t') != std::string::npos) {
          tab = " (line " + std::to_string(n) + " is indented with a tab: YAML indents with spaces only)";
          break;
        }
      }
    }
    // Control bytes in yaml-cpp's message (the character it stopped at) written as \xNN, not sent to the terminal.
    std::string message;
    for (const char c : e.msg) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
        message += hex;
      } else {
        message += c;
      }
    }
    throw ConfigError({name_for_errors, line},
                      "malformed YAML: " + message + (e.mark.line + 1 > lines ? " (at the end of the file)" : "") + tab);
  }
  std::vector<YAML::Node> open;
  std::size_t visited = 0;
  refuse_repeated_keys_and_cycles(root, name_for_errors, open, visited);
  refuse_dangling_last_line(text, name_for_errors);
  return root;
}

YAML::Node load_file(const std::filesystem::path& path) {
  // (A folder opens as an empty stream: it read as "DIR:1: a graph file must be a YAML map".)
  if (std::error_code ec; std::filesystem::is_directory(path, ec))
    throw ConfigError("'" + path.string() + "' is a folder, not a YAML file");
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read '" + path.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return load_text(ss.str(), path.string());
}

}  // namespace drape::yaml
