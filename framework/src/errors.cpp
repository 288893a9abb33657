#include <drape/errors.hpp>

#include <algorithm>
#include <cctype>

namespace drape {

std::string SourceLocation::str() const {
  if (file.empty()) return "<unknown>";
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

ConfigError::ConfigError(const SourceLocation& where, const std::string& what)
    : Error(where.str() + ": " + what) {}

namespace {
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}
}  // namespace

std::vector<std::string> closest_matches(const std::string& name,
                                         const std::vector<std::string>& candidates,
                                         std::size_t max_count) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    // A typo changes a few characters; a prefix or substring also counts as close.
    const bool contains = !name.empty() && (c.find(name) != std::string::npos || name.find(c) != std::string::npos);
    const std::size_t limit = std::max<std::size_t>(2, std::max(name.size(), c.size()) / 3);
    if (d <= limit || contains) scored.emplace_back(contains ? std::min<std::size_t>(d, 1) : d, c);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& s : scored) {
    if (out.size() == max_count) break;
    out.push_back(s.second);
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
