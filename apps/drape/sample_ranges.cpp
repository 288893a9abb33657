#include "sample_ranges.hpp"

#include <cmath>

#include "command.hpp"

namespace drape::cli {

Range parse_range(const std::string& option, const std::string& text) {
  bool nan = false;
  try {
    std::size_t used = 0;
    const auto colon = text.find(':');
    if (colon == std::string::npos) {
      const double v = std::stod(text, &used);
      // (NaN is no number here: "--bmi nan" was told "a range needs --sample", NaN != NaN.)
      if (used == text.size() && std::isfinite(v)) return {v, v};
      nan = std::isnan(v);
    } else {
      const double lo = std::stod(text.substr(0, colon), &used);
      std::size_t used2 = 0;
      const double hi = std::stod(text.substr(colon + 1), &used2);
      if (used == colon && used2 == text.size() - colon - 1 && std::isfinite(lo) && std::isfinite(hi) && lo <= hi)
        return {lo, hi};
      nan = std::isnan(lo) || std::isnan(hi);
    }
  } catch (const std::exception&) {
  }
  if (nan) throw UsageError("--" + option + " '" + text + "': not a number (NaN)");
  throw UsageError("--" + option + " '" + text + "': expected a finite number or a range lo:hi with lo <= hi");
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  try {
    if (slash != std::string::npos) {
      std::size_t used = 0, used2 = 0;
      const long i = std::stol(text.substr(0, slash), &used), n = std::stol(text.substr(slash + 1), &used2);
      if (used == slash && used2 == text.size() - slash - 1 && n >= 1 && i >= 0 && i < n)
        return {static_cast<std::size_t>(i), static_cast<std::size_t>(n)};
    }
  } catch (const std::exception&) {
  }
  throw UsageError("--shard '" + text + "': expected i/N with 0 <= i < N");
}

}  // namespace drape::cli
