// Shipped files by name (drape/io/shipped_files.hpp). The source tree is
// compiled in as DRAPE_SOURCE_DATA_DIR (framework/CMakeLists.txt).
#include <drape/io/shipped_files.hpp>

#include <drape/errors.hpp>

#include <boost/dll/runtime_symbol_info.hpp>

#include <cstdlib>

namespace drape {

namespace fs = std::filesystem;

namespace {

// <prefix>/share/drape for the prefix whose lib/ holds this library. The path
// the loader used is resolved first: the Python module reaches the library
// through $ORIGIN/../../.., which parent_path() would walk up lexically wrong.
fs::path installed_data_dir() {
  std::error_code ec;
  fs::path self = boost::dll::this_line_location(ec);
  if (!ec) self = fs::weakly_canonical(self, ec);
  if (ec) return {};
  return self.parent_path().parent_path() / "share" / "drape";
}

void add_dir(std::vector<fs::path>& dirs, const fs::path& dir) {
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return;
  for (const auto& d : dirs)
    if (fs::equivalent(d, dir, ec)) return;  // a build tree installed into itself, DRAPE_DATA_DIR = the source
  dirs.push_back(dir);
}

}  // namespace

std::vector<fs::path> shipped_data_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("DRAPE_DATA_DIR"); env && *env) add_dir(dirs, env);
  add_dir(dirs, installed_data_dir());
#ifdef DRAPE_SOURCE_DATA_DIR
  add_dir(dirs, DRAPE_SOURCE_DATA_DIR);
#endif
  return dirs;
}

fs::path locate_shipped_file(const fs::path& name) {
  std::error_code ec;
  if (name.empty()) return {};
  if (fs::exists(name, ec)) return name;
  if (name.is_absolute()) return {};
  for (const auto& dir : shipped_data_dirs())
    if (fs::exists(dir / name, ec)) return dir / name;
  return {};
}

fs::path find_input_file(const fs::path& name) {
  if (fs::path found = locate_shipped_file(name); !found.empty()) return found;
  std::error_code ec;
  std::string where = fs::current_path(ec).string();
  if (!name.is_absolute())
    for (const auto& dir : shipped_data_dirs()) where += ", " + dir.string();
  throw ConfigError(name.string() + ": no such file" + (name.is_absolute() ? "" : " (looked in " + where + ")"));
}

}  // namespace drape
