#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/fnv1a.hpp>
#include <drape/io/write_failure.hpp>

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <cstring>
#include <csignal>
#include <cerrno>
#include <climits>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace drape {
namespace {

// This machine, in the temporaries' names: on a folder shared by the
// machines of a cluster, a process is known alive or dead only on its own.
// Eight hex digits of its name's hash, not the name (up to 64 characters):
// the temporary's name must stay within what write_failure_cause allows for
// (255 less kLongestName's 220).
std::string host_tag() {
  char name[HOST_NAME_MAX + 1] = {};
  if (::gethostname(name, sizeof name - 1) != 0) name[0] = '\0';
  return Fnv1a().text(name).hex().substr(0, 8);
}

// A temporary of `target` left by a process of this machine that is gone (a
// job killed mid-write: the rename that would have moved it into place never
// came). Named as write_atomically names them: .<stem>.tmp<pid>-<n>@<host tag><ext>.
bool stale_temporary(const std::string& name, const fs::path& target, const std::string& host) {
  const std::string head = "." + target.stem().string() + ".tmp", tail = "@" + host + target.extension().string();
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return false;
  const std::string middle = name.substr(head.size(), name.size() - head.size() - tail.size());  // <pid>-<n>
  const std::size_t dash = middle.find('-');
  if (dash == 0 || dash == std::string::npos || middle.find_first_not_of("0123456789-") != std::string::npos) return false;
  long pid = 0;
  try {
    pid = std::stol(middle.substr(0, dash));
  } catch (const std::exception&) {
    return false;
  }
  if (pid <= 0 || pid == ::getpid()) return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;  // (EPERM: alive, another user's)
}

// Removes the temporaries of `target` that killed jobs of this machine left
// in its folder (a killed expand of a full dataset left 18 MB a kill).
void remove_stale_temporaries(const fs::path& dir, const fs::path& target, const std::string& host) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (stale_temporary(name, target, host)) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

// The temporaries being written now, for a terminating signal's handler
// (output_lock.cpp): a job stopped by Ctrl-C or SIGTERM mid-write left its
// temporary (18 MB for a dataset expand; an outside check) until the next
// write of that target. Fixed slots of plain characters: unlink is safe in a
// handler, and nothing there allocates.
constexpr int kInFlight = 16;
constexpr std::size_t kPath = 4096;
char in_flight[kInFlight][kPath];
volatile std::sig_atomic_t in_flight_used[kInFlight];
std::mutex in_flight_mutex;

// A slot holding `tmp` for the write's duration, or none (-1) when all are
// taken or the path is too long: then only the next write removes it.
class InFlight {
 public:
  explicit InFlight(const fs::path& tmp) {
    const std::string path = tmp.string();
    if (path.size() >= kPath) return;
    const std::lock_guard<std::mutex> lock(in_flight_mutex);
    for (int i = 0; i < kInFlight; ++i)
      if (!in_flight_used[i]) {
        std::memcpy(in_flight[i], path.c_str(), path.size() + 1);
        in_flight_used[i] = 1;
        slot_ = i;
        return;
      }
  }
  ~InFlight() {
    if (slot_ < 0) return;
    const std::lock_guard<std::mutex> lock(in_flight_mutex);
    in_flight_used[slot_] = 0;
  }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace

void unlink_temporaries_in_flight() noexcept {
  for (int i = 0; i < kInFlight; ++i)
    if (in_flight_used[i]) ::unlink(in_flight[i]);
}

void remove_stale_temporaries(const fs::path& target) {
  static const std::string host = host_tag();
  remove_stale_temporaries(target.has_parent_path() ? target.parent_path() : fs::path("."), target, host);
}

fs::path output_target(const fs::path& given) {
  std::error_code ec;
  fs::path target = given;
  // Followed link by link (a link to a file not yet made has no canonical
  // path); a chain longer than the system's own limit is left as given.
  for (int hop = 0; hop < 40 && fs::is_symlink(fs::symlink_status(target, ec)); ++hop) {
    const fs::path next = fs::read_symlink(target, ec);
    if (ec) break;
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  if (target != given)
    if (fs::path resolved = fs::weakly_canonical(target, ec); !ec) target = std::move(resolved);
  const fs::file_status status = fs::status(target, ec);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status))
    throw ConfigError("cannot write '" + given.string() + "': it is a device, a pipe or a socket, not a file; name a file");
  return target;
}

void write_atomically(const fs::path& given, const std::function<void(const fs::path&)>& write) {
  const fs::path target = output_target(given);
  static std::atomic<unsigned> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  // A missing or read-only folder is the user's to fix: ConfigError (exit 2).
  if (const std::string cause = write_failure_cause(target, false); !cause.empty())
    throw ConfigError("cannot write '" + target.string() + "': " + cause);
  static const std::string host = host_tag();
  remove_stale_temporaries(dir, target, host);
  // Keep the extension last: some writers (assimp) pick the format from it.
  const fs::path tmp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                              std::to_string(counter++) + "@" + host + target.extension().string());
  const InFlight held(tmp);  // (removed by a terminating signal's handler too)
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
    // (The writer's message may begin with the cause already: said once.)
    if (message.rfind(cause + ": ", 0) == 0) message.erase(0, cause.size() + 2);
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
