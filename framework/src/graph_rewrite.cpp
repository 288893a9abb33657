#include "graph_rewrite.hpp"

#include <algorithm>
#include <string>

namespace drape::detail {
namespace {

// How many references to `name` as a value the graph holds: node and loss
// inputs, and outputs.
int uses_of(const GraphSpec& spec, const std::string& name) {
  int uses = 0;
  for (const auto& n : spec.nodes)
    for (const auto& [port, ref] : n.inputs) uses += ref.node == name;
  for (const auto& [out, ref] : spec.outputs) uses += ref.node == name;
  return uses;
}

bool declared_one_row(const GraphSpec& spec, const std::string& input) {
  for (const auto& [name, dims] : spec.inputs)
    if (name == input) return dims.first[0] == "1";
  return false;
}

bool name_taken(const GraphSpec& spec, const std::string& name) {
  for (const auto& n : spec.nodes)
    if (n.name == name) return true;
  for (const auto& [input, dims] : spec.inputs)
    if (input == name) return true;
  for (const auto& [out, ref] : spec.outputs)
    if (out == name) return true;
  return false;
}

const PortRef* input_on(const NodeSpec& n, const std::string& port, std::size_t position) {
  std::size_t positional = 0;
  for (const auto& [p, ref] : n.inputs) {
    if (p == port) return &ref;
    if (p.empty() && positional++ == position) return &ref;
  }
  return nullptr;
}

}  // namespace

std::optional<GraphSpec> gather_before_repeated_concat(const GraphSpec& spec) {
  GraphSpec out = spec;
  bool changed = false;
  for (std::size_t g = 0; g < out.nodes.size(); ++g) {
    const NodeSpec gather = out.nodes[g];
    if (gather.is_loss || gather.type != "gather" || gather.inputs.size() != 1) continue;
    const PortRef& from = gather.inputs[0].second;
    if (!from.port.empty() && from.port != "out") continue;
    const auto c = std::find_if(out.nodes.begin(), out.nodes.end(), [&](const NodeSpec& n) { return n.name == from.node; });
    if (c == out.nodes.end() || c->is_loss || c->type != "concat" || c->inputs.size() != 2) continue;
    const PortRef* a = input_on(*c, "a", 0);
    const PortRef* b = input_on(*c, "b", 1);
    if (!a || !b || !b->port.empty() || !declared_one_row(spec, b->node)) continue;
    if (uses_of(out, c->name) != 1) continue;  // the concat's rows are read elsewhere too
    const std::string rows = gather.name + "_rows";
    if (name_taken(out, rows)) continue;

    NodeSpec row_gather = gather;
    row_gather.name = rows;
    row_gather.inputs = {{gather.inputs[0].first, *a}};
    NodeSpec concat = *c;
    concat.name = gather.name;
    concat.inputs = {{"a", PortRef{rows, "", c->where}}, {"b", *b}};
    const std::string removed = c->name;
    out.nodes[g] = concat;
    out.nodes.push_back(row_gather);
    out.nodes.erase(std::find_if(out.nodes.begin(), out.nodes.end(), [&](const NodeSpec& n) { return n.name == removed; }));
    changed = true;
    g = static_cast<std::size_t>(-1);  // indices moved: look again from the start
  }
  if (!changed) return std::nullopt;
  return out;
}

}  // namespace drape::detail
