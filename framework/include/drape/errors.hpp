#pragma once
// Error types: one tree under Error. The CLI maps ConfigError (and its
// UsageError) to exit code 2 (usage or configuration problems the user can fix
// in their files or command line) and any other Error to exit code 1; Python
// raises drape.ConfigError (a ValueError) and drape.Error (a RuntimeError).
#include <stdexcept>
#include <string>
#include <vector>

namespace drape {

// Where something came from: a file and a 1-based line (0 = unknown).
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string str() const;  // "file:line" or "file" or "<unknown>"
};

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad configuration, bad arguments or bad input files: the user's to fix.
class ConfigError : public Error {
 public:
  using Error::Error;
  ConfigError(const SourceLocation& where, const std::string& what);
};

// A bad command line or call: an option missing, malformed or given with
// another it excludes. A ConfigError (exit code 2; Python's ValueError) that
// the drape program prints with the command's usage instead of "error:".
class UsageError : public ConfigError {
 public:
  using ConfigError::ConfigError;
};

// An interrupted run (a training state, a dataset's partial file) made with
// other inputs or settings than the command asks now, so it cannot be
// continued: what a caller that may start over (drape experiment) catches,
// rather than reading "cannot resume" in a message.
class ResumeRefused : public ConfigError {
 public:
  using ConfigError::ConfigError;
};

// Up to `max_count` candidates closest to `name` by edit distance (case-insensitive),
// only those close enough to be plausible typos, best first.
std::vector<std::string> closest_matches(const std::string& name,
                                         const std::vector<std::string>& candidates,
                                         std::size_t max_count = 3);

// "; did you mean 'a', 'b'?" or "" when nothing is close.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace drape
