// `drape plugins`: every plugin found on the search path, with its ports and parameters.
#include "command.hpp"

#include <drape/param_range.hpp>
#include <drape/registry.hpp>

#include <algorithm>
#include <cctype>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape plugins");
  opts.add_options()("kind", po::value<std::string>(), "only plugins of this kind (encoder, decoder, loss, energy, op, ...)")(
      "brief", "one line per plugin");
  po::variables_map vm;
  if (!parse("drape plugins [--kind K] [--brief]", args, opts, {}, vm)) return 0;
  const Registry& reg = Registry::load_default(plugin_path(vm));
  std::string kind = vm.count("kind") ? vm["kind"].as<std::string>() : "";
  // Kinds in any case ("Loss"), and a misspelt one answered with the kinds there are.
  std::transform(kind.begin(), kind.end(), kind.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::size_t shown = 0;
  for (const PluginDescriptor* d : reg.all()) {
    if (!kind.empty() && d->kind != kind) continue;
    ++shown;
    std::cout << d->kind << " " << d->name << (vm.count("brief") ? " - " : "\n  ") << d->doc << "\n";
    if (vm.count("brief")) continue;
    std::cout << "  file: " << d->file << "\n";
    for (const auto& p : d->inputs) std::cout << "  in   " << p.name << (p.optional ? " (optional)" : "") << ": " << p.doc << "\n";
    for (const auto& p : d->outputs) std::cout << "  out  " << p.name << ": " << p.doc << "\n";
    for (const auto& p : d->params) {
      std::cout << "  param " << p.name << " (" << to_string(p.type) << ", default " << p.default_value;
      if (p.min || p.max) std::cout << ", range " << range_text(p);
      if (!p.choices.empty()) {
        std::cout << ", one of";
        for (const auto& c : p.choices) std::cout << " " << c;
      }
      std::cout << "): " << p.doc << "\n";
    }
  }
  for (const auto& r : reg.refused()) std::cout << "refused " << r << "\n";
  if (!kind.empty() && shown == 0) {
    std::vector<std::string> kinds;
    for (const PluginDescriptor* d : reg.all())
      if (std::find(kinds.begin(), kinds.end(), d->kind) == kinds.end()) kinds.push_back(d->kind);
    std::string list;
    for (const std::string& k : kinds) list += (list.empty() ? "" : ", ") + k;
    std::cerr << "drape plugins: no plugin of kind '" << kind << "'" << did_you_mean(kind, kinds) << " (kinds: " << list << ")\n";
    return 2;
  }
  std::cout << shown << " plugins\n";
  return 0;
}

const RegisterCommand registration{{"plugins", "list every plugin with its kind, ports and parameters", run}};

}  // namespace
}  // namespace drape::cli
