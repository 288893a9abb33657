// OutputLock (output_lock.hpp).
#include <drape/errors.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/io/write_failure.hpp>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>
#include <mutex>

namespace fs = std::filesystem;

namespace drape {

fs::path OutputLock::lock_file(const fs::path& output) { return fs::path(output.string() + ".lock"); }

namespace {

// An output named as one of drape's working files of another output: a
// job's unfinished dataset (<out>.partial), its lock (<out>.lock), a
// training's state (<model>.h5.state). The lock below covers <out>, not
// them, so a merge --out z.h5.partial --force replaced a running generate's
// partial file and the generate then sealed another run's drapes as its own.
void refuse_working_file_name(const fs::path& output) {
  const std::string name = output.filename().string();
  for (const std::string suffix : {".partial", ".lock", ".state"}) {
    if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const fs::path owner = output.parent_path() / name.substr(0, name.size() - suffix.size());
    if (suffix == ".state" && owner.extension() != ".h5") continue;  // (a user's own .state file)
    const std::string what = suffix == ".partial" ? "the unfinished file a job writing '" + owner.string() + "' keeps"
                             : suffix == ".lock"  ? "the lock of a job writing '" + owner.string() + "'"
                                                  : "the training state of the model '" + owner.string() + "'";
    throw ConfigError("cannot write '" + output.string() + "': that name is drape's own, " + what +
                      " (the job's lock does not cover it); give the output another name");
  }
}

// The lock files this process holds, for the signal handler below: a job
// stopped with Ctrl-C or SIGTERM left its <out>.lock next to an output it
// never wrote (an outside check), which looks like an output in use. The
// kernel drops the lock itself; the file is removed here, with unlink (safe
// in a handler), before the signal's default action ends the process.
constexpr int kHeldLocks = 8;
constexpr std::size_t kLockPath = 4096;
char held_locks[kHeldLocks][kLockPath];
volatile std::sig_atomic_t held_in_use[kHeldLocks];
volatile std::sig_atomic_t held_resumable[kHeldLocks];

volatile std::sig_atomic_t stop_deferred = 0;  // DeferredStop scopes open
volatile std::sig_atomic_t pending_stop = 0;   // a signal that came in one

extern "C" void remove_held_locks(int signal) {
  if (stop_deferred > 0) {
    pending_stop = signal;  // ended when the last scope closes (~DeferredStop)
    return;
  }
  for (int i = 0; i < kHeldLocks; ++i)
    if (held_in_use[i]) ::unlink(held_locks[i]);
  unlink_temporaries_in_flight();  // (the output being written, half done)
  // One line of why the job ended (an outside check's experiment ended by
  // SIGTERM with exit 143 and no word). write(2) is safe in a handler.
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : signal == SIGHUP ? "SIGHUP" : nullptr;
  if (name) {
    // A job that writes its output whole at the end (a single-body optimize,
    // a merge) keeps nothing: it said "what was finished is kept" and a
    // second run started from the beginning (an outside check).
    bool resumable = false;
    for (int i = 0; i < kHeldLocks; ++i) resumable = resumable || (held_in_use[i] && held_resumable[i]);
    constexpr const char head[] = "\ndrape: stopped by ";
    constexpr const char kept[] = ": what was finished is kept; run the same command again to go on (drape train: with --resume)\n";
    constexpr const char lost[] = ": nothing was written (the output is written whole when the job ends); run the command again to start over\n";
    [[maybe_unused]] ssize_t ignored = ::write(2, head, sizeof head - 1);
    std::size_t length = 0;
    while (name[length] != '\0') ++length;
    ignored = ::write(2, name, length);
    if (resumable) ignored = ::write(2, kept, sizeof kept - 1);
    else ignored = ::write(2, lost, sizeof lost - 1);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

int hold_for_signals(const fs::path& lock, bool resumable) {
  // Only where the signal would end the process anyway (its default
  // action): one ignored stays ignored, and one a host handles (Python's
  // SIGINT, a KeyboardInterrupt) is the host's; removing the file there
  // while the job goes on would let a second writer in.
  // At every lock, not once: a signal whose handler went back to its
  // default since (a forked child's) gets ours again; ours stays as it is.
  // (SIGPIPE: `drape train ... | head -1` ended the job and left its lock;
  // SIGHUP: the terminal it ran in closed.)
  for (const int signal : {SIGINT, SIGTERM, SIGPIPE, SIGHUP}) {
    struct sigaction now {};
    if (::sigaction(signal, nullptr, &now) != 0 || (now.sa_flags & SA_SIGINFO) || now.sa_handler != SIG_DFL) continue;
    struct sigaction ours {};
    ours.sa_handler = remove_held_locks;
    sigemptyset(&ours.sa_mask);
    ::sigaction(signal, &ours, nullptr);
  }
  const std::string path = lock.string();
  if (path.size() >= kLockPath) return -1;
  for (int i = 0; i < kHeldLocks; ++i)
    if (!held_in_use[i]) {
      std::memcpy(held_locks[i], path.c_str(), path.size() + 1);
      held_resumable[i] = resumable ? 1 : 0;
      held_in_use[i] = 1;
      return i;
    }
  return -1;
}

}  // namespace

OutputLock::OutputLock(const fs::path& given, const std::string& command, bool resumable) : path_(lock_file(output_target(given))) {
  // The output the lock is of: a link's target, so that both names share one lock.
  const fs::path output = fs::path(path_).replace_extension();
  refuse_working_file_name(output);
  // A dead run's temporaries of this output and of its working files (a
  // training state, a partial dataset) first: on a full disk they are what
  // fills it.
  for (const char* working : {"", ".state", ".partial"}) remove_stale_temporaries(output.string() + working);
  if (const std::string cause = write_failure_cause(output, false); !cause.empty())
    throw ConfigError("cannot write '" + output.string() + "': " + cause);
  for (;;) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw ConfigError("cannot create the lock file '" + path_.string() + "': " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      char holder[512] = {};
      const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
      ::close(fd);
      if (error != EWOULDBLOCK) throw ConfigError("cannot lock '" + path_.string() + "': " + std::strerror(error));
      std::string who = n > 0 ? std::string(holder, static_cast<std::size_t>(n)) : std::string("another process");
      while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
      throw ConfigError(output.string() + " is in use: another drape process is writing it (" + who +
                        "); wait until it ends or stop it, then run this again. A second writer is refused whatever "
                        "its flags (--resume and --force included): the two would overwrite each other");
    }
    // The holder before us may have removed the lock file between our open
    // and our lock: then we hold a lock on a file no one else can see, so
    // start again on whatever the path names now.
    struct stat held {}, named {};
    if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string me = "pid " + std::to_string(::getpid()) + ", " + command + "\n";
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, me.data(), me.size(), 0) < 0) {
        // The lock holds without its note; the message then says "another process".
      }
      fd_ = fd;
      slot_ = hold_for_signals(path_, resumable);
      return;
    }
    ::close(fd);
  }
}

DeferredStop::DeferredStop() { stop_deferred = stop_deferred + 1; }

DeferredStop::~DeferredStop() {
  stop_deferred = stop_deferred - 1;
  if (stop_deferred == 0 && pending_stop != 0) {
    const int signal = pending_stop;
    pending_stop = 0;
    std::cout.flush();  // the lines written in the scope (an epoch's log), before the process ends
    remove_held_locks(signal);
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  if (slot_ >= 0) held_in_use[slot_] = 0;
  // Removed while still held: a process that opened it just now finds, once
  // it gets the lock, that the path no longer names it, and starts again.
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace drape
