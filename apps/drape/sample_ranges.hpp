#pragma once
// Command-line ranges of body measurements ("38" or "10:65") and shards of a
// job array ("3/16"); the types are the framework's (services/dataset_generation.hpp).
#include <drape/services/dataset_generation.hpp>

#include <string>

namespace drape::cli {

using Range = drape::SampleRange;
using drape::Shard;

// Throws UsageError naming the option when the text is neither a number nor lo:hi with lo <= hi.
Range parse_range(const std::string& option, const std::string& text);

// "i/N" with 0 <= i < N; UsageError naming --shard otherwise.
Shard parse_shard(const std::string& text);

}  // namespace drape::cli
