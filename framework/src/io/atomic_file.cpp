#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/write_failure.hpp>

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
  // A missing or read-only folder is the user's to fix: ConfigError (exit 2).
  if (const std::string cause = write_failure_cause(target); !cause.empty())
    throw ConfigError("cannot write '" + target.string() + "': " + cause);
  // Keep the extension last: some writers (assimp) pick the format from it.
  const fs::path tmp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                              std::to_string(counter++) + target.extension().string());
  try {
    write(tmp);
  } catch (const Error& e) {
    // The writer's message names the temporary file and at best the library
    // call that failed: name the user's file, and the cause when it is known
    // (asked before the partial file is removed, which frees its space).
    const std::string cause = write_failure_cause(target);
    fs::remove(tmp, ec);
    std::string message = e.what();
    for (std::size_t at; (at = message.find(tmp.string())) != std::string::npos;)
      message.replace(at, tmp.string().size(), target.string());
    if (cause.empty()) {
      if (message == e.what()) throw;
      if (dynamic_cast<const ConfigError*>(&e)) throw ConfigError(message);  // the kind of error is kept
      throw Error(message);
    }
    throw Error("cannot write '" + target.string() + "': " + cause + " (" + message + ")");
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // (before remove() overwrites ec: it said "Success")
    fs::remove(tmp, ec);
    throw Error("cannot move the finished file into place at '" + target.string() + "': " + why);
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
