// Where the shipped pretrained model is: $DRAPE_MODEL, else models/ among the
// shipped files' folders (drape/io/shipped_files.hpp: $DRAPE_DATA_DIR, an
// installed share/drape, the source tree of a build). Not relative to the
// current folder: the default must not change with where a command runs.
#include <drape/io/shipped_files.hpp>
#include <drape/training/model.hpp>

#include <cstdlib>

namespace drape {

namespace fs = std::filesystem;

fs::path shipped_model_path(const std::string& file_name) {
  std::error_code ec;
  for (const auto& dir : shipped_data_dirs())
    if (const fs::path file = dir / "models" / file_name; fs::is_regular_file(file, ec)) return file;
  return {};
}

fs::path default_model_path() {
  if (const char* env = std::getenv("DRAPE_MODEL"); env && *env) return env;
  return shipped_model_path(kDefaultModelFile);
}

}  // namespace drape
