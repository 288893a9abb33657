#pragma once
// Command-line ranges of body measurements: "38" or "10:65".
#include <string>

namespace drape::cli {

struct Range {
  double lo, hi;
};

// Throws UsageError naming the option when the text is neither a number nor lo:hi with lo <= hi.
Range parse_range(const std::string& option, const std::string& text);

}  // namespace drape::cli
