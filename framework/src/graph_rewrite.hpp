#pragma once
// Rewrites of a graph as written into one that computes the same values with
// less work, applied when a Graph is built (graph.cpp). The graph as written
// stays the graph's spec: checkpoints store it, and `drape model set` edits it.
#include <drape/graph.hpp>

#include <optional>

namespace drape::detail {

// A row gather after a concat whose second input is one row repeated
// (`gathered = gather(concat(features, grade))`, the sized models' graphs)
// copies every one of the concat's rows and keeps a few: on the encoder's
// 6,490 body rows, of which the gather keeps the garment's 991, the concat
// was a sixth of the network's time. Gathered first, then concatenated,
// the rows are the same floats and the gradients the same sums. Applies
// where the concat feeds nothing but the gather and its second input is a
// graph input declared with one row; the gather keeps its name (it is now
// the concat) and the row gather is named `<gather>_rows`. nullopt: nothing
// to rewrite.
std::optional<GraphSpec> gather_before_repeated_concat(const GraphSpec& spec);

}  // namespace drape::detail
