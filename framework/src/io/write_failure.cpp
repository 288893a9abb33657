// write_failure_cause, check_writable_output, refuse_output_among_inputs (write_failure.hpp).
#include <drape/errors.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/write_failure.hpp>

#include <sys/statvfs.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace drape {

namespace {
// Below this much free space a failed write is put down to a full disk:
// HDF5 and assimp extend a file by up to a few hundred kilobytes at a time.
constexpr unsigned long long kNearlyFull = 1ull << 20;
// The longest output file name: 255 (NAME_MAX) less the temporary files' additions.
constexpr std::size_t kLongestName = 220;

fs::path folder_of(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }
}  // namespace

std::string write_failure_cause(const fs::path& file, bool failed) {
  const fs::path folder = folder_of(file);
  std::error_code ec;
  if (fs::is_directory(file, ec)) return "it is a folder; give a file name";
  // A name the file system takes alone may not take drape's temporary and
  // partial files beside it (".<name>.tmp<pid>-<n>.h5", "<name>.partial",
  // "<name>.state"): a 240-character --out failed after a training epoch.
  if (const std::size_t n = file.filename().string().size(); n > kLongestName)
    return "its name is " + std::to_string(n) + " characters long; drape writes files named after it with up to " +
           std::to_string(255 - kLongestName) + " more, past the 255 a file system takes: give a shorter name";
  if (!fs::is_directory(folder, ec))
    return fs::exists(folder, ec) ? "'" + folder.string() + "' is a file, not a folder"
                                  : "folder '" + folder.string() + "' does not exist";
  struct statvfs info {};
  if (::statvfs(folder.c_str(), &info) == 0) {
    if (info.f_flag & ST_RDONLY) return "cannot write in '" + folder.string() + "' (read-only file system)";
    // /proc, /sys: no blocks at all, not a full disk.
    if (info.f_blocks == 0) return "cannot write files in '" + folder.string() + "' (a virtual file system, such as /proc)";
    if (static_cast<unsigned long long>(info.f_bavail) * info.f_frsize < (failed ? kNearlyFull : 1ull))
      return "no space left on '" + folder.string() + "'";
  }
  if (::access(folder.c_str(), W_OK) != 0) return "cannot write in '" + folder.string() + "' (permission denied)";
  return {};
}

void check_writable_output(const fs::path& file, const std::string& option) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw ConfigError(option + " " + file.string() + ": is a folder; give a file name");
  const std::string cause = write_failure_cause(file, false);
  if (!cause.empty()) throw ConfigError(option + " " + file.string() + ": " + cause);
}

void check_output_folder(const fs::path& folder, const std::string& option) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    throw ConfigError(option + " " + folder.string() + ": is a file, not a folder");
  // The nearest folder that exists: the output's files go there, or the folders made in it.
  fs::path existing = folder.empty() ? fs::path(".") : folder;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing.parent_path() != existing)
    existing = existing.parent_path();
  if (!fs::exists(existing, ec)) existing = ".";
  if (!fs::is_directory(existing, ec))
    throw ConfigError(option + " " + folder.string() + ": '" + existing.string() + "' is a file, not a folder");
  const std::string cause = write_failure_cause(existing / "probe", false);
  if (!cause.empty()) throw ConfigError(option + " " + folder.string() + ": " + cause);
}

void refuse_output_among_inputs(const fs::path& out, const std::vector<fs::path>& inputs, const std::string& option) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  for (const fs::path& in : inputs)
    if (fs::exists(in, ec) && fs::equivalent(in, out, ec))
      throw ConfigError(option + " " + out.string() + " is also an input (" + in.string() +
                        "): the job would write over what it reads; name another file");
}

namespace {
// A drape model file (a checkpoint that records its assets); anything that
// does not read as one is not.
bool is_drape_model(const fs::path& file) {
  try {
    return read_checkpoint(file).meta.count("assets") > 0;
  } catch (const std::exception&) {
    return false;
  }
}
}  // namespace

void refuse_replacing_other_than_a_model(const fs::path& out, const std::string& option) {
  std::error_code ec;
  if (!fs::exists(out, ec) || fs::is_directory(out, ec)) return;  // a folder: the writer names it as one
  if (is_drape_model(out)) return;
  throw ConfigError(option + " " + out.string() + " exists and is not a drape model (a dataset, a training state, "
                    "another file): a model is written over a model only; name a new file, or move that one away");
}

void refuse_replacing_a_model(const fs::path& out, const std::string& option) {
  std::error_code ec;
  if (fs::is_regular_file(out, ec) && is_drape_model(out))
    throw ConfigError(option + " " + out.string() + " is a drape model: --force replaces a file of this command's "
                      "kind, not a model; name another file, or move that one away");
}

}  // namespace drape
