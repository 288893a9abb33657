#pragma once
// One writer per output. A long job (generate, train, optimize, dataset merge)
// holds an exclusive lock on <output>.lock for as long as it runs, taken
// before it looks at the output at all, so that a second job on the same
// output is refused whatever its flags (--resume or --force would otherwise
// rewrite a file another process is writing). The kernel drops the lock when
// the process ends, killed or not; the lock file itself is removed on a
// normal end, and on SIGINT or SIGTERM (not on SIGKILL, which nothing sees).
#include <filesystem>
#include <string>

namespace drape {

class OutputLock {
 public:
  // Throws ConfigError naming the process that holds the lock (its pid and
  // command) when another process writes `output`; `command` is recorded in
  // the lock file for that message. `resumable`: the job keeps what it
  // finished and a second run goes on from there (generate, train, optimize
  // --data), which a stopped job says; else it says nothing was written.
  OutputLock(const std::filesystem::path& output, const std::string& command, bool resumable = false);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  static std::filesystem::path lock_file(const std::filesystem::path& output);

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  int slot_ = -1;  // its place among the locks a SIGINT or SIGTERM removes (output_lock.cpp)
};

// While one lives, a SIGINT, SIGTERM or SIGHUP that would end the job (its
// lock's handler) waits until the scope ends, so that files written together
// stay together: a training stopped between its model and its state left the
// model an epoch ahead and that epoch's log line unprinted (an outside
// check). Any thread may take the signal; the handler sees the flag. Nest-safe.
class DeferredStop {
 public:
  DeferredStop();
  ~DeferredStop();
  DeferredStop(const DeferredStop&) = delete;
  DeferredStop& operator=(const DeferredStop&) = delete;
};

}  // namespace drape
