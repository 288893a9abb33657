#include "targets.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace drape::makehuman {
namespace {

Target read_target(const fs::path& file, const std::string& name) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError("cannot read MakeHuman target '" + file.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  Target t;
  t.name = name;
  std::vector<float> values;
  std::size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    const char* p = text.data() + pos;
    const char* e = text.data() + end;
    pos = end + 1;
    while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    if (p == e || *p == '#') continue;
    int index = 0;
    auto r = std::from_chars(p, e, index);
    float xyz[3];
    bool ok = r.ec == std::errc();
    p = r.ptr;
    for (float& v : xyz) {
      while (p < e && *p == ' ') ++p;
      // from_chars for float rejects a leading '+' but accepts ".5" only from GCC 12 on: both fine here.
      auto rv = std::from_chars(p, e, v);
      ok = ok && rv.ec == std::errc();
      p = rv.ptr;
    }
    if (!ok || index < 0)
      throw ConfigError(SourceLocation{file.string(), static_cast<int>(line_no)}, "malformed target line");
    t.index.push_back(index);
    values.insert(values.end(), xyz, xyz + 3);
  }
  t.offset = Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>(values.data(),
                                                                                  static_cast<Eigen::Index>(t.index.size()), 3);
  return t;
}

double tent_max(double v) { return std::max(0.0, 2 * v - 1); }
double tent_min(double v) { return std::max(0.0, 1 - 2 * v); }

}  // namespace

std::vector<Target> load_macro_targets(const fs::path& root) {
  const fs::path dir = root / "targets" / "macrodetails";
  if (!fs::is_directory(dir)) throw ConfigError("MakeHuman targets not found: '" + dir.string() + "' is not a folder");
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".target") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Target> out;
  for (const auto& f : files) {
    std::string name = fs::relative(f, dir).replace_extension().string();
    out.push_back(read_target(f, name));
  }
  if (out.empty()) throw ConfigError("no .target files under '" + dir.string() + "'");
  return out;
}

double target_weight(const std::string& path_name, const Sliders& s) {
  const std::string name = fs::path(path_name).filename().string();
  const double ethnic_sum = s.african + s.asian + s.caucasian;
  const std::map<std::string, double> keys = {
      {"male", s.gender},
      {"female", 1 - s.gender},
      {"young", 1.0},  // only the young age (25 years, slider 0.5) ships
      {"universal", 1.0},
      {"african", ethnic_sum > 0 ? s.african / ethnic_sum : 1.0 / 3},
      {"asian", ethnic_sum > 0 ? s.asian / ethnic_sum : 1.0 / 3},
      {"caucasian", ethnic_sum > 0 ? s.caucasian / ethnic_sum : 1.0 / 3},
      {"maxmuscle", tent_max(s.muscle)},
      {"minmuscle", tent_min(s.muscle)},
      {"averagemuscle", 1 - tent_max(s.muscle) - tent_min(s.muscle)},
      {"maxweight", tent_max(s.weight)},
      {"minweight", tent_min(s.weight)},
      {"averageweight", 1 - tent_max(s.weight) - tent_min(s.weight)},
      {"maxheight", tent_max(s.height)},
      {"minheight", tent_min(s.height)},
      {"idealproportions", tent_max(s.proportions)},
      {"uncommonproportions", tent_min(s.proportions)},
  };
  double w = 1.0;
  std::stringstream ss(name);
  std::string key;
  while (std::getline(ss, key, '-')) {
    auto it = keys.find(key);
    if (it == keys.end()) throw Error("MakeHuman target '" + path_name + "': unknown key '" + key + "'");
    w *= it->second;
  }
  return w;
}

Eigen::MatrixX3d apply_targets(const Eigen::MatrixX3d& base, const std::vector<Target>& targets, const Sliders& s) {
  Eigen::MatrixX3d v = base;
  for (const auto& t : targets) {
    const double w = target_weight(t.name, s);
    if (w == 0.0) continue;
    for (std::size_t i = 0; i < t.index.size(); ++i) {
      if (t.index[i] >= v.rows()) throw ConfigError("MakeHuman target '" + t.name + "' moves vertex " + std::to_string(t.index[i]) +
                                                    " but the base mesh has " + std::to_string(v.rows()));
      v.row(t.index[i]) += w * t.offset.row(static_cast<Eigen::Index>(i)).cast<double>();
    }
  }
  return v;
}

}  // namespace drape::makehuman
