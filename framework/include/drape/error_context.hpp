#pragma once
// Who said it: the framework puts a plugin's name in front of the errors its
// code throws and the warnings it gives (warnings.hpp), at the calls it makes
// into the plugin (the factories, an energy's every method, a garment's
// build, a node's forward and backward; the graph names a node's setup
// itself), so plugins write plain messages and a name is written once, in
// its descriptor.
#include <string>

namespace drape {

// `message` with "<name>: " in front, unless it already starts with the name.
std::string with_context(const std::string& name, const std::string& message);

// Inside a catch block: rethrows the exception being handled with
// with_context(name, what()) as its message, keeping its type (UsageError,
// ConfigError or Error); any other std::exception but std::bad_alloc becomes
// an Error so named; anything else is rethrown unchanged.
[[noreturn]] void rethrow_with_context(const std::string& name);

// Inside a catch block: a ConfigError (or UsageError) that names no file yet
// is rethrown at `where` ("file:line: "), with with_context(label, what()):
// a plugin's own check of its parameters knows no file, the caller that read
// them (a graph's node, a scene's garment) does. Anything else is rethrown
// unchanged.
struct SourceLocation;
[[noreturn]] void rethrow_at(const SourceLocation& where, const std::string& label);

// While one lives, warn() on this thread puts `name` in front of its text.
class ContextScope {
 public:
  explicit ContextScope(const std::string& name);
  ~ContextScope();
  ContextScope(const ContextScope&) = delete;
  ContextScope& operator=(const ContextScope&) = delete;

 private:
  const std::string* previous_;
};

// The innermost ContextScope's name on this thread, or null.
const std::string* current_context();

// Calls f(), naming `name` in any drape error it throws and any warning it gives.
template <class F>
decltype(auto) in_context(const std::string& name, F&& f) {
  try {
    const ContextScope scope(name);
    return f();
  } catch (...) {
    rethrow_with_context(name);
  }
}

}  // namespace drape
