#include <drape/scene/size_table.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace drape {

double SizeChoice::garment_girth(const std::string& s) const {
  for (const auto& [name, g] : girth)
    if (name == s) return g;
  return 0.0;
}

std::string SizeChoice::summary() const {
  char head[160];
  std::snprintf(head, sizeof head, "body girth %.3f m (chest or belly); design ease %.1f %%; ease by size:", body_girth,
                100.0 * design_ease);
  std::string out = head;
  for (const auto& [name, g] : girth) {
    char item[64];
    std::snprintf(item, sizeof item, " %s %+.1f %%", name.c_str(), 100.0 * ease(name));
    out += item;
  }
  if (size.empty()) return out + ": no size is as large as the body, the garment does not fit it";
  return out + ": size " + size;
}

SizeChoice SizeTable::choose(double body_girth) const {
  SizeChoice choice;
  choice.girth = girth;
  choice.design_ease = design_ease;
  choice.body_girth = body_girth;
  double best = std::numeric_limits<double>::infinity();
  // A garment made tight (less ease on its design body than kMinimumEase:
  // MakeHuman's T-shirt has -3.4 % on MakeHuman's mean body) is worn as tight
  // as it was designed; otherwise no size smaller than the body.
  const double floor = std::min(kMinimumEase, design_ease);
  for (const auto& [name, g] : girth) {
    const double ease = choice.ease(name);
    if (ease >= floor && std::abs(ease - design_ease) < best) {
      best = std::abs(ease - design_ease);
      choice.size = name;
    }
  }
  return choice;
}

std::string SizeTable::names() const {
  std::string out;
  for (const auto& [name, g] : girth) out += (out.empty() ? "" : ", ") + name;
  return out;
}

double SizeTable::grade(const std::string& size) const {
  double of_size = 0.0, of_design = 0.0;
  for (const auto& [name, g] : girth) {
    if (name == size) of_size = g;
    if (name == design) of_design = g;
  }
  if (!(of_size > 0.0)) {
    std::vector<std::string> sizes;
    for (const auto& [name, g] : girth) sizes.push_back(name);
    throw ConfigError("garment size '" + size + "': the garment's sizes are " + names() + did_you_mean(size, sizes));
  }
  if (!(of_design > 0.0)) throw ConfigError("the size chart names no girth for its design size '" + design + "'");
  return of_size / of_design;
}

SizeTable SizeTable::join(const SizeTable& a, const SizeTable& b) {
  // Both are read from the same text form (to_text's 17 digits), so a chart
  // measured again from the same meshes reads back equal to the last bit.
  if (a.design != b.design || a.design_ease != b.design_ease)
    throw ConfigError("the size charts differ in their design size (" + a.design + " with ease " +
                      std::to_string(a.design_ease) + " against " + b.design + " with ease " +
                      std::to_string(b.design_ease) + ")");
  SizeTable joined = a;
  for (const auto& [name, g] : b.girth) {
    const auto same = std::find_if(a.girth.begin(), a.girth.end(), [&](const auto& s) { return s.first == name; });
    if (same == a.girth.end()) {
      joined.girth.emplace_back(name, g);
    } else if (same->second != g) {
      char why[200];
      std::snprintf(why, sizeof why, "the size charts differ in size %s (%.6f m around against %.6f m)", name.c_str(),
                    same->second, g);
      throw ConfigError(why);
    }
  }
  std::stable_sort(joined.girth.begin(), joined.girth.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
  return joined;
}

std::string SizeTable::to_text() const {
  std::ostringstream o;
  o.precision(17);
  o << "design=" << design << "; design_ease=" << design_ease << ";";
  for (std::size_t i = 0; i < girth.size(); ++i) o << (i ? ", " : " ") << girth[i].first << "=" << girth[i].second;
  return o.str();
}

namespace {

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// "name=value" into its parts; false when there is no '=' or either side is empty.
bool split_pair(const std::string& item, std::string& name, std::string& value) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) return false;
  name = trimmed(item.substr(0, eq));
  value = trimmed(item.substr(eq + 1));
  return !name.empty() && !value.empty();
}

double number(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double v = std::numeric_limits<double>::quiet_NaN();
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !std::isfinite(v)) throw ConfigError(what + ": '" + text + "' is not a number");
  return v;
}

}  // namespace

SizeTable SizeTable::parse(const std::string& text, const std::string& what) {
  const std::string bad = what + ": not a size chart (\"design=NAME; design_ease=E; NAME=GIRTH, ...\"): ";
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ';');) parts.push_back(part);
  if (parts.size() != 3) throw ConfigError(bad + "three parts separated by ';' expected");
  SizeTable t;
  std::string name, value;
  if (!split_pair(parts[0], name, value) || name != "design") throw ConfigError(bad + "no design size first");
  t.design = value;
  if (!split_pair(parts[1], name, value) || name != "design_ease") throw ConfigError(bad + "no design_ease second");
  t.design_ease = number(value, what + " design_ease");
  std::stringstream sizes(parts[2]);
  for (std::string item; std::getline(sizes, item, ',');) {
    if (!split_pair(item, name, value)) throw ConfigError(bad + "'" + trimmed(item) + "' is not NAME=GIRTH");
    const double g = number(value, what + " girth of " + name);
    if (!(g > 0.0)) throw ConfigError(what + ": the girth of size " + name + " must be positive");
    t.girth.emplace_back(name, g);
  }
  if (t.girth.empty()) throw ConfigError(bad + "no sizes");
  t.grade(t.design);  // the design size must be among them
  return t;
}

}  // namespace drape
