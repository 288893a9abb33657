#include <drape/atomic_file.hpp>
#include <drape/errors.hpp>

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace drape {

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error("cannot write '" + target.string() + "': folder '" + dir.string() + "' does not exist");
  // Keep the extension last: some writers (assimp) pick the format from it.
  const fs::path tmp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                              std::to_string(counter++) + target.extension().string());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error("cannot move the finished file into place at '" + target.string() + "': " + ec.message());
  }
}

void write_text_atomically(const fs::path& target, const std::string& text) {
  write_atomically(target, [&](const fs::path& tmp) {
    std::ofstream f(tmp);
    f << text;
    f.close();
    if (!f) throw Error("cannot write '" + target.string() + "'");
  });
}

}  // namespace drape
