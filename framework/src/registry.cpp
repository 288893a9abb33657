#include <drape/bodies/body.hpp>
#include "plugin_energy.hpp"

#include <drape/energy_node.hpp>
#include <drape/error_context.hpp>
#include <drape/registry.hpp>
#include <drape/warnings.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <boost/dll/import.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace drape {

struct Registry::Library {
  boost::dll::shared_library handle;
  fs::path file;
};

Registry::Registry() = default;
Registry::~Registry() {
  plugins_.clear();  // the descriptors' code lives in the libraries: drop them first
  libraries_.clear();
}

namespace {

constexpr const char* kPrefix = "libdrape_plugin_";

bool is_plugin_file(const fs::path& p) {
  const std::string name = p.filename().string();
  return name.rfind(kPrefix, 0) == 0 && p.extension() == ".so";
}

// The plugins shipped with this framework library: <libdir>/drape/plugins when
// installed, <build>/plugins in the build tree (the library is <build>/framework/).
std::vector<fs::path> shipped_plugin_dirs() {
  std::vector<fs::path> out;
  std::error_code ec;
  const fs::path self = boost::dll::this_line_location(ec);
  if (ec) return out;
  const fs::path dir = self.parent_path();
  for (const fs::path& candidate : {dir / "drape" / "plugins", dir.parent_path() / "plugins"})
    if (fs::is_directory(candidate)) out.push_back(candidate);
  return out;
}

}  // namespace

std::vector<fs::path> Registry::search_path(const std::vector<std::string>& extra) {
  std::vector<fs::path> dirs;
  for (const auto& e : extra)
    if (!e.empty()) dirs.emplace_back(e);
  if (const char* env = std::getenv("DRAPE_PLUGIN_PATH")) {
    std::stringstream ss(env);
    std::string item;
    while (std::getline(ss, item, ':'))
      if (!item.empty()) dirs.emplace_back(item);
  }
  for (const auto& d : shipped_plugin_dirs()) dirs.push_back(d);
  return dirs;
}

Registry& Registry::load_default(const std::vector<std::string>& extra) {
  // Never destroyed: plugin code must stay mapped for as long as anything built
  // from it may live, which includes static objects destroyed at exit.
  static Registry* instance = [&] {
    auto* r = new Registry;
    r->load_path(search_path(extra));
    return r;
  }();
  return *instance;
}

void Registry::load_path(const std::vector<fs::path>& dirs) {
  std::set<fs::path> seen_dirs;
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
      if (fs::exists(dir, ec) && is_plugin_file(dir)) load_file(dir);
      // (A single plugin file is an entry too: say which of the two it is not.)
      else if (!fs::exists(dir, ec)) warn("plugin path entry '" + dir.string() + "' does not exist");
      else warn("plugin path entry '" + dir.string() + "' is neither a folder nor a plugin library (" + kPrefix + "<name>.so)");
      continue;
    }
    const fs::path canonical = fs::canonical(dir, ec);
    if (!seen_dirs.insert(canonical).second) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && is_plugin_file(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) load_file(f);
  }
}

namespace {

// What makes a descriptor unusable, whatever else is on the path.
void check_descriptor(const PluginDescriptor& d) {
  // A graph, a scene and a model's file name plugins by these words: one
  // that is empty, or holds a space or a '.' (node.param), cannot be written there.
  const bool word = !d.name.empty() && std::all_of(d.name.begin(), d.name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-';
  });
  if (!word)
    throw ConfigError(d.file + ": plugin name '" + d.name +
                      "' is not a word of letters, digits, '_' and '-' (a graph names its plugins by it)");
  if (d.abi_version != kAbiVersion)
    throw ConfigError(d.file + ": plugin '" + d.name + "' declares ABI " + std::to_string(d.abi_version) +
                      " but this drape uses ABI " + std::to_string(kAbiVersion));
  const int factories = !!d.create_node + !!d.create_energy + !!d.create_body + !!d.create_garment;
  if (factories != 1)
    throw ConfigError(d.file + ": plugin '" + d.name +
                      "' must define exactly one of create_node, create_energy, create_body, create_garment");
  // Its defaults, as a graph that sets none would take them: a default its
  // own type or range refuses failed at the first graph that used the
  // plugin, blamed on "<default>" in the user's graph.
  try {
    const Params defaults(d.params, {}, "plugin '" + d.name + "'");
  } catch (const std::exception& e) {
    std::string why = e.what();
    if (why.rfind("<default>: ", 0) == 0) why.erase(0, 11);
    throw ConfigError(d.file + ": " + why + " (the plugin's own default)");
  }
}

// The energy adapter's ports, and a name another plugin already has (an
// error naming both files: which one a graph meant cannot be told).
void complete_descriptor(const Registry& registry, PluginDescriptor& d) {
  if (d.create_energy && d.inputs.empty() && d.outputs.empty()) {  // the EnergyNode adapter's ports
    d.inputs = {{"x", "garment vertex positions [vertices, 3]"}};
    d.outputs = {{"energy", "the energy of each sample [1, 1]"}};
  }
  if (const PluginDescriptor* other = registry.find(d.name))
    throw ConfigError("two plugins are named '" + d.name + "': " + other->file + " and " + d.file +
                      "; remove one from the plugin path");
}

}  // namespace

void Registry::load_file(const fs::path& file) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(file, ec);
  if (ec) throw ConfigError("cannot open plugin '" + file.string() + "': " + ec.message());
  for (const auto& lib : libraries_)
    if (lib->file == canonical) return;  // the same file reached twice through the path

  auto lib = std::make_unique<Library>();
  lib->file = canonical;
  // rtld_now: a plugin with an unresolved symbol is refused at load time with the
  // loader's message, instead of crashing in the middle of a run.
  try {
    lib->handle.load(canonical.string(), boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local);
  } catch (const std::exception& e) {
    refused_.push_back(canonical.string() + ": cannot be loaded (" + e.what() + ")");
    warn("refused plugin " + refused_.back());
    return;
  }
  if (!lib->handle.has("drape_plugin_abi_version") || !lib->handle.has("drape_plugin_factory")) {
    const bool abi = lib->handle.has("drape_plugin_abi_version"), factory = lib->handle.has("drape_plugin_factory");
    const std::string missing = !abi && !factory ? "drape_plugin_abi_version and drape_plugin_factory"
                                : !abi           ? "drape_plugin_abi_version"
                                                 : "drape_plugin_factory";
    refused_.push_back(canonical.string() + ": not a drape plugin (it exports no " + missing +
                       "; DRAPE_PLUGIN_EXPORT(plugins) defines both)");
    warn("refused plugin " + refused_.back());
    return;
  }
  // Checked before calling anything else: the factory's return type is only
  // meaningful when both sides agree on the ABI.
  const int abi = lib->handle.get<int()>("drape_plugin_abi_version")();
  if (abi != kAbiVersion) {
    refused_.push_back(canonical.string() + ": built for drape plugin ABI " + std::to_string(abi) +
                       ", but this drape uses ABI " + std::to_string(kAbiVersion) + "; rebuild the plugin");
    warn("refused plugin " + refused_.back());
    return;
  }
  auto factory = lib->handle.get_alias<PluginFactory>("drape_plugin_factory");
  PluginList list;
  // A library whose list fails to build is refused like one that cannot be
  // loaded: one bad file on the path must not stop a command that does not
  // use it, nor `drape plugins`, the command that finds it.
  try {
    list = factory();
  } catch (const std::exception& e) {
    refused_.push_back(canonical.string() + ": its plugin list failed to build (" + e.what() + ")");
    warn("refused plugin " + refused_.back());
    return;
  }
  // A descriptor the framework cannot use (no factory, a name no graph can
  // write, a default its own parameter refuses, a name given twice in the
  // list) refuses its library, as above: an outside check's one bad
  // descriptor stopped every command, `drape plugins` too. A name another
  // library on the path already has stays an error (exit 2, both files
  // named): which of the two a graph meant cannot be told.
  std::set<std::string> listed;
  for (auto& d : list) {
    d.file = canonical.string();
    std::string fault;
    if (!listed.insert(d.name).second) fault = "it lists two plugins named '" + d.name + "'";
    else
      try {
        check_descriptor(d);
      } catch (const std::exception& e) {
        fault = e.what();
      }
    if (!fault.empty()) {
      const std::string prefix = canonical.string() + ": ";
      if (fault.rfind(prefix, 0) == 0) fault.erase(0, prefix.size());
      refused_.push_back(canonical.string() + ": " + fault);
      warn("refused plugin " + refused_.back());
      return;
    }
  }
  for (auto& d : list) complete_descriptor(*this, d);  // (each checked above)
  libraries_.push_back(std::move(lib));
  for (auto& d : list) plugins_.push_back(std::move(d));
}

void Registry::add(PluginDescriptor d) {
  if (d.file.empty()) d.file = "<in-process>";
  validate(d);
  plugins_.push_back(std::move(d));
}

void Registry::validate(PluginDescriptor& d) const {
  check_descriptor(d);
  complete_descriptor(*this, d);
}

const PluginDescriptor* Registry::find(const std::string& name) const {
  for (const auto& d : plugins_)
    if (d.name == name) return &d;
  return nullptr;
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> out;
  for (const auto& d : plugins_) out.push_back(d.name);
  std::sort(out.begin(), out.end());
  return out;
}

const PluginDescriptor& Registry::get(const std::string& name) const {
  if (const auto* d = find(name)) return *d;
  std::string msg = "unknown plugin type '" + name + "'" + did_you_mean(name, names());
  if (plugins_.empty()) msg += " (no plugins are loaded: check --plugin-path or DRAPE_PLUGIN_PATH)";
  throw ConfigError(msg + refused_notes());
}

std::string Registry::refused_notes() const {
  std::string notes;
  for (const auto& r : refused_) notes += "\n  note: refused " + r;
  return notes;
}

std::vector<const PluginDescriptor*> Registry::all() const {
  std::vector<const PluginDescriptor*> out;
  for (const auto& d : plugins_) out.push_back(&d);
  std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return std::tie(a->kind, a->name) < std::tie(b->kind, b->name); });
  return out;
}

namespace {
// What a plugin's factory made, or a ConfigError naming it when it made
// nothing (a null node crashed drape and the Python interpreter).
template <class T>
std::unique_ptr<T> not_null(const std::string& name, const char* factory, std::unique_ptr<T> made) {
  if (!made) throw ConfigError("plugin '" + name + "': its " + factory + " returned nothing (a null pointer)");
  return made;
}

// "an energy", "an encoder", "a loss": a plugin's kind with its article.
std::string a_kind(const std::string& kind) {
  return (kind.find_first_of("aeiou") == 0 ? "an " : "a ") + kind;
}
}  // namespace

// The factories run in the plugin's name (error_context.hpp): a plugin's
// errors come out as "<name>: ..." without the plugin writing its name.
std::unique_ptr<Node> Registry::create_node(const std::string& name, const Params& params) const {
  const PluginDescriptor& d = get(name);
  if (d.create_node) return not_null(name, "create_node", in_context(name, [&] { return d.create_node(params); }));
  if (d.create_energy) return std::make_unique<EnergyNode>(create_energy(name, params));
  throw ConfigError("'" + name + "' is " + a_kind(d.kind) + "; it cannot be a node of a graph");
}

std::unique_ptr<BodyModel> Registry::create_body(const std::string& name, const Params& params) const {
  const PluginDescriptor& d = get(name);
  if (!d.create_body) throw ConfigError("'" + name + "' is " + a_kind(d.kind) + ", not a body model");
  return not_null(name, "create_body", in_context(name, [&] { return d.create_body(params); }));
}

namespace {

// A garment template whose build() names its plugin in its errors.
class PluginGarment final : public GarmentSource {
 public:
  PluginGarment(std::string name, std::unique_ptr<GarmentSource> source)
      : name_(std::move(name)), source_(std::move(source)) {}
  Garment build() const override {
    return in_context(name_, [&] { return source_->build(); });
  }

 private:
  std::string name_;
  std::unique_ptr<GarmentSource> source_;
};

}  // namespace

std::unique_ptr<GarmentSource> Registry::create_garment(const std::string& name, const Params& params) const {
  const PluginDescriptor& d = get(name);
  if (!d.create_garment) throw ConfigError("'" + name + "' is " + a_kind(d.kind) + ", not a garment template");
  return std::make_unique<PluginGarment>(name, not_null(name, "create_garment", in_context(name, [&] { return d.create_garment(params); })));
}

// Every call into the energy names the plugin in its errors (plugin_energy.hpp).
std::unique_ptr<Energy> Registry::create_energy(const std::string& name, const Params& params) const {
  const PluginDescriptor& d = get(name);
  if (!d.create_energy) throw ConfigError("'" + name + "' is " + a_kind(d.kind) + ", not an energy");
  return std::make_unique<PluginEnergy>(name, not_null(name, "create_energy", in_context(name, [&] { return d.create_energy(params); })));
}

}  // namespace drape
