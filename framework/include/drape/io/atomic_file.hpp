#pragma once
// Outputs are written atomically: to a temporary file next to the target, then
// renamed over it, so a crash or kill never leaves a half-written file behind.
#include <filesystem>
#include <functional>
#include <string>

namespace drape {

// The file an output named `given` is written to: a symbolic link's target
// (the link is kept; renaming over it replaced the link with a file, and a
// job on the link and one on its target did not share a lock), else `given`.
// ConfigError for a device, a pipe or a socket there: renamed over, it was
// replaced by a regular file (as root, `--out /dev/null` would have replaced
// the system's /dev/null); an outside check.
std::filesystem::path output_target(const std::filesystem::path& given);

// Calls write(tmp_path), then renames tmp_path to `target`. If write throws,
// the temporary file is removed and the exception propagates; `target` is untouched.
// The temporary lives in the same directory (rename is atomic only within a filesystem).
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// Removes the temporaries of `target` that processes of this machine, now
// gone, left beside it (killed mid-write); write_atomically does so itself.
// A job's lock (output_lock.hpp) does it for its output's files before it
// checks the folder has room: a job that died of a full disk left its
// temporary filling it, and the next run was refused "no space left".
void remove_stale_temporaries(const std::filesystem::path& target);

// Unlinks the temporaries write_atomically is writing now. Safe in a signal
// handler (unlink only): a job's terminating signal removes them with its
// lock (output_lock.cpp), instead of leaving them to the next write.
void unlink_temporaries_in_flight() noexcept;

// A text file (reports, pictures), atomically; Error when it cannot be written.
void write_text_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace drape
