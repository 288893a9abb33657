// Where the shipped pretrained model is: an installed drape keeps it under
// share/ next to lib/, a build tree reads it from the source tree (the path is
// compiled in as DRAPE_SOURCE_MODEL, see framework/CMakeLists.txt).
#include <drape/training/model.hpp>

#include <boost/dll/runtime_symbol_info.hpp>

#include <cstdlib>

namespace drape {

namespace fs = std::filesystem;

namespace {
constexpr const char* kModelName = "tshirt-coarse.h5";
}

fs::path default_model_path() {
  std::error_code ec;
  if (const char* env = std::getenv("DRAPE_MODEL"); env && *env) return env;
  // lib/libdrape_framework.so, as the loader named it: the Python module finds it through
  // $ORIGIN/../../.., which parent_path() would walk up lexically into the wrong folder.
  fs::path self = boost::dll::this_line_location(ec);
  if (!ec) self = fs::weakly_canonical(self, ec);
  if (!ec) {
    const fs::path installed = self.parent_path().parent_path() / "share" / "drape" / "models" / kModelName;
    if (fs::is_regular_file(installed, ec)) return installed;
  }
#ifdef DRAPE_SOURCE_MODEL_DIR
  const fs::path source = fs::path(DRAPE_SOURCE_MODEL_DIR) / kModelName;
  if (fs::is_regular_file(source, ec)) return source;
#endif
  return {};
}

}  // namespace drape
