// `drape graph check FILE`: validates a graph as a whole and prints its nodes and shapes.
#include "command.hpp"

#include <filesystem>

#include <drape/assets/assets.hpp>
#include <drape/graph.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/bodies/body.hpp>
#include <drape/params.hpp>
#include <drape/training/model.hpp>

#include <algorithm>
#include <cctype>
#include <set>

#include <iomanip>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

std::map<std::string, int> parse_dims(const std::vector<std::string>& items) {
  std::map<std::string, int> dims;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    try {
      if (eq == std::string::npos) throw std::invalid_argument(item);
      dims[item.substr(0, eq)] = std::stoi(item.substr(eq + 1));
    } catch (const std::exception&) {
      throw UsageError("--dim wants name=size, got '" + item + "'");
    }
  }
  return dims;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape graph check");
  opts.add_options()("action", po::value<std::string>()->required(), "check")(
      "file", po::value<std::string>()->required(), "graph YAML file")(
      "dim", po::value<std::vector<std::string>>()->composing(), "a symbolic size, name=value (repeatable)")(
      "garment", po::value<std::string>()->default_value("tshirt"), "garment template whose assets give the sizes")(
      "resolution", po::value<std::string>(), "garment resolution (tshirt: default | coarse | a vertex count)")(
      "k", po::value<int>()->default_value(1000), "eigenvectors in the assets")(
      "body-param", po::value<std::vector<std::string>>()->composing(),
      "a parameter of the template's body model, name=value (repeatable): rig=human for the human rig's graphs")(
      "encoder-body", po::value<std::string>(),
      "a body model whose vertices the encoder reads, as drape train --encoder-body (a graph with a resample_body node: "
      "the human rig's graphs/human/*.yaml take parametric)")(
      "no-assets", "bind no garment template: every symbolic size must come from --dim");
  // `drape graph FILE` (the action left out) read FILE as the action and
  // said "missing file" of the file it was given (an outside check).
  if (!args.empty() && args[0] != "check" && args[0].rfind("-", 0) != 0) {
    std::error_code ec;
    const std::string ext = std::filesystem::path(args[0]).extension().string();
    if (ext == ".yaml" || ext == ".yml" || std::filesystem::is_regular_file(args[0], ec))
      throw UsageError("'" + args[0] + "' is a file, not an action: drape graph check " + args[0]);
  }
  po::positional_options_description pos;
  pos.add("action", 1).add("file", 1);
  po::variables_map vm;
  if (!parse("drape graph check FILE [--dim name=size ...]", args, opts, pos, vm)) return 0;
  if (vm["action"].as<std::string>() != "check") throw UsageError("unknown action '" + vm["action"].as<std::string>() + "' (try: check)");

  const Registry& reg = Registry::load_default(plugin_path(vm));
  GraphOptions options;
  if (vm.count("dim")) options.dims = parse_dims(vm["dim"].as<std::vector<std::string>>());
  const GraphSpec spec = parse_graph_file(find_input_file(vm["file"].as<std::string>()));
  // A --dim the graph's inputs never name sizes nothing (a misspelt
  // --dim garmnet_vertices=991 was taken and the template's size used).
  std::set<std::string> symbolic;
  for (const auto& input : spec.inputs)
    for (const std::string& d : input.second.first)
      if (!d.empty() && !std::isdigit(static_cast<unsigned char>(d[0]))) symbolic.insert(d);
  for (const auto& [name, size] : options.dims)
    if (!symbolic.count(name)) {
      std::string known;
      for (const std::string& s : symbolic) known += (known.empty() ? "" : ", ") + s;
      throw UsageError("--dim " + name + ": the graph's inputs use no size of that name (" +
                       (known.empty() ? std::string("they use none") : "they use " + known) + ")");
    }
  // A model's graph (checked on a template's assets): the inputs drape
  // feeds, as drape train checks them (an outside check's input `extra` was
  // "ok" here and refused by train). --no-assets checks any graph's wiring.
  if (!vm.count("no-assets")) check_graph_inputs(spec);
  // Sizes such as garment_vertices and the garment itself come from the
  // template's assets (cached after the first build); --dim overrides.
  std::shared_ptr<const Assets> assets;
  if (!vm.count("no-assets")) {
    AssetsSpec as;
    as.garment = vm["garment"].as<std::string>();
    if (vm.count("resolution")) as.garment_params["resolution"] = vm["resolution"].as<std::string>();
    as.eigen_k = vm["k"].as<int>();
    if (vm.count("encoder-body")) as.encoder_body = vm["encoder-body"].as<std::string>();
    if (vm.count("body-param"))
      for (const std::string& item : vm["body-param"].as<std::vector<std::string>>()) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
          throw UsageError("--body-param '" + item + "': expected name=value (e.g. rig=human)");
        as.body_params[item.substr(0, eq)] = item.substr(eq + 1);
      }
    assets = build_assets(reg, as);
    options.assets = assets.get();
    for (const auto& [name, size] : assets->dims()) options.dims.emplace(name, size);
    // body_params: the template's body model's shape parameters, which a
    // dataset of it stores (train takes the size from the dataset).
    if (!options.dims.count("body_params")) {
      const PluginDescriptor& body = reg.get(as.body_model);
      options.dims["body_params"] =
          static_cast<int>(reg.create_body(as.body_model, Params(body.params, {}, "body '" + as.body_model + "'"))->shape_names().size());
    }
  }
  const Graph graph(spec, reg, options);

  std::cout << spec.file << ": ok\n";
  // What drape train refuses beyond the graph's wiring (check_trainable): said, since a graph may be meant
  // for a forward pass alone.
  const auto& nodes = spec.nodes;
  if (std::none_of(nodes.begin(), nodes.end(), [](const NodeSpec& n) { return n.is_loss && n.weight != 0.0; }))
    std::cout << "  note: no loss has a weight above 0, so drape train refuses this graph (nothing to train with)\n";
  for (const auto& name : graph.input_names()) std::cout << "  input  " << name << " " << graph.input_shape(name).str() << "\n";
  std::size_t total = 0;
  for (const auto& n : graph.describe()) {
    std::cout << "  " << (n.is_loss ? "loss   " : "node   ") << std::left << std::setw(16) << n.name << std::setw(16)
              << n.type << " " << n.kind;
    if (n.is_loss) std::cout << " (weight " << n.weight << ")";
    if (n.weight_count) std::cout << ", " << n.weight_count << " weights";
    std::cout << "\n";
    for (const auto& i : n.inputs) std::cout << "         in  " << i << "\n";
    for (const auto& [port, shape] : n.outputs) std::cout << "         out " << port << " " << shape.str() << "\n";
    total += n.weight_count;
  }
  for (const auto& name : graph.output_names()) std::cout << "  output " << name << "\n";
  std::cout << "  " << total << " learnable weights, " << graph.flops_per_sample() << " multiply-adds per sample\n";
  return 0;
}

const RegisterCommand registration{{"graph", "check a graph file: types, ports, shapes, cycles", run}};

}  // namespace
}  // namespace drape::cli
