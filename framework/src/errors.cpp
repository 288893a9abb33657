#include <drape/errors.hpp>

#include <algorithm>
#include <cctype>
#include <tuple>
#include <vector>

namespace drape {

std::string SourceLocation::str() const {
  if (file.empty()) return "<unknown>";
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

ConfigError::ConfigError(const SourceLocation& where, const std::string& what)
    : Error(where.str() + ": " + what) {}

namespace {
// Optimal string alignment distance, case-insensitive: the edits of
// Levenshtein's distance plus a swap of two neighbouring characters, the
// commonest typo ('mpl' for 'mlp' is one edit, not two).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}
}  // namespace

std::vector<std::string> closest_matches(const std::string& name,
                                         const std::vector<std::string>& candidates,
                                         std::size_t max_count) {
  // (score, edits, name): a substring scores as one edit, and among equal
  // scores the fewer true edits come first ('mlp' before 'add_template' for
  // 'mpl', which it contains).
  std::vector<std::tuple<std::size_t, std::size_t, std::string>> scored;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    // A typo changes a few characters; a prefix or substring also counts as close.
    const bool contains = !name.empty() && (c.find(name) != std::string::npos || name.find(c) != std::string::npos);
    const std::size_t limit = std::max<std::size_t>(2, std::max(name.size(), c.size()) / 3);
    if (d <= limit || contains) scored.emplace_back(contains ? std::min<std::size_t>(d, 1) : d, d, c);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& s : scored) {
    if (out.size() == max_count) break;
    out.push_back(std::get<2>(s));
  }
  return out;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates) {
  const auto close = closest_matches(name, candidates);
  if (close.empty()) return "";
  std::string s = "; did you mean ";
  for (std::size_t i = 0; i < close.size(); ++i) s += (i ? ", '" : "'") + close[i] + "'";
  return s + "?";
}

}  // namespace drape
