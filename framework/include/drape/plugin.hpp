#pragma once
// The plugin ABI. A plugin is a shared library named libdrape_plugin_<name>.so
// that exports two symbols:
//   drape_plugin_abi_version   (extern "C" int(), checked before anything else)
//   drape_plugin_factory       (Boost.DLL alias, returns the descriptors)
// Use DRAPE_PLUGIN_EXPORT(fn) once per library to define both.
#include <drape/node.hpp>
#include <drape/params.hpp>

#include <boost/config.hpp>
#include <boost/dll/alias.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

// Bump whenever a type in a public header changes layout or a virtual signature.
#define DRAPE_ABI_VERSION 11

namespace drape {

inline constexpr int kAbiVersion = DRAPE_ABI_VERSION;

// What the factories make, declared only: a plugin includes the header of its
// own kind (energy.hpp, bodies/body.hpp), so a network node does not pull in
// the physics' types.
class Energy;
class BodyModel;
class GarmentSource;

struct PortSpec {
  std::string name;
  std::string doc;
  bool optional = false;  // an input that may be left unconnected
};

struct PluginDescriptor {
  std::string kind;  // encoder, decoder, loss, energy, op, ...
  std::string name;  // the `type:` used in graphs and scenes
  std::string doc;
  int abi_version = kAbiVersion;
  std::vector<PortSpec> inputs;
  std::vector<PortSpec> outputs;
  std::vector<ParamSpec> params;
  // Exactly one of these is set: learning nodes build a Node, energies an Energy
  // (the registry wraps energies into EnergyNode when a graph uses them as losses),
  // body models a BodyModel, garment templates a GarmentSource.
  std::function<std::unique_ptr<Node>(const Params&)> create_node;
  std::function<std::unique_ptr<Energy>(const Params&)> create_energy;
  std::function<std::unique_ptr<BodyModel>(const Params&)> create_body;
  std::function<std::unique_ptr<GarmentSource>(const Params&)> create_garment;

  std::string file;  // filled in by the registry: the library it came from
};

using PluginList = std::vector<PluginDescriptor>;
using PluginFactory = PluginList();

}  // namespace drape

// Defines the two exported symbols. `fn` is a function `drape::PluginList fn()`.
#define DRAPE_PLUGIN_EXPORT(fn)                                                  \
  extern "C" BOOST_SYMBOL_EXPORT int drape_plugin_abi_version() { return DRAPE_ABI_VERSION; } \
  BOOST_DLL_ALIAS(fn, drape_plugin_factory)
