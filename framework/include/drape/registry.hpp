#pragma once
// Finds, checks and loads plugin libraries, and builds nodes and energies by name.
#include <drape/plugin.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class Registry {
 public:
  Registry();
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // The search path, in order: `extra` (--plugin-path), $DRAPE_PLUGIN_PATH
  // (colon-separated), then the plugins shipped with this framework library
  // (build tree or install prefix, found relative to the library itself).
  static std::vector<std::filesystem::path> search_path(const std::vector<std::string>& extra = {});

  // Loads every libdrape_plugin_*.so in the search path. Libraries built for
  // another ABI are refused (see refused()); two plugins of one name throw
  // ConfigError naming both files.
  static Registry& load_default(const std::vector<std::string>& extra = {});
  void load_path(const std::vector<std::filesystem::path>& dirs);
  void load_file(const std::filesystem::path& file);
  // Registers a descriptor built in-process (embedding applications, tests).
  // Same checks as for a library; `file` is set to "<in-process>" when empty.
  void add(PluginDescriptor descriptor);

  // Throws ConfigError listing close matches when `name` is unknown.
  const PluginDescriptor& get(const std::string& name) const;
  const PluginDescriptor* find(const std::string& name) const;
  std::vector<const PluginDescriptor*> all() const;  // sorted by kind, then name
  std::vector<std::string> names() const;

  // Libraries that were found but not loaded, with the reason.
  const std::vector<std::string>& refused() const { return refused_; }
  // "\n  note: refused <file>: <reason>" for each: added to every "unknown
  // plugin" error, since the plugin asked for may be one of them.
  std::string refused_notes() const;

  // A node for `name`; energies come wrapped as EnergyNode.
  std::unique_ptr<Node> create_node(const std::string& name, const Params& params) const;
  std::unique_ptr<Energy> create_energy(const std::string& name, const Params& params) const;
  std::unique_ptr<BodyModel> create_body(const std::string& name, const Params& params) const;
  std::unique_ptr<GarmentSource> create_garment(const std::string& name, const Params& params) const;

 private:
  void validate(PluginDescriptor& descriptor) const;
  struct Library;
  std::vector<std::unique_ptr<Library>> libraries_;
  std::vector<PluginDescriptor> plugins_;
  std::vector<std::string> refused_;
};

}  // namespace drape
