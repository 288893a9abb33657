#pragma once
// Command-line ranges of body measurements ("38" or "10:65") and shards of a
// job array ("3/16").
#include <cstddef>
#include <string>

namespace drape::cli {

struct Range {
  double lo, hi;
};

// Throws UsageError naming the option when the text is neither a number nor lo:hi with lo <= hi.
Range parse_range(const std::string& option, const std::string& text);

// Part `index` of `count` of a list: the contiguous block [n i / N, n (i + 1) / N),
// so the shards of a job array cover every item once, in order.
struct Shard {
  std::size_t index = 0, count = 1;
  std::size_t first(std::size_t n) const { return n * index / count; }
  std::size_t last(std::size_t n) const { return n * (index + 1) / count; }  // one past
};

// "i/N" with 0 <= i < N; UsageError naming --shard otherwise.
Shard parse_shard(const std::string& text);

}  // namespace drape::cli
