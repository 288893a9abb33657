// with_context, rethrow_with_context, ContextScope (error_context.hpp).
#include <drape/error_context.hpp>
#include <drape/errors.hpp>

#include <new>

namespace drape {
namespace {

thread_local const std::string* innermost_context = nullptr;

}  // namespace

ContextScope::ContextScope(const std::string& name) : previous_(innermost_context) { innermost_context = &name; }

ContextScope::~ContextScope() { innermost_context = previous_; }

const std::string* current_context() { return innermost_context; }

std::string with_context(const std::string& name, const std::string& message) {
  // "barrier: ..." and "barrier needs ..." already say who.
  const bool named = message.compare(0, name.size(), name) == 0 &&
                     (message.size() == name.size() || message[name.size()] == ':' || message[name.size()] == ' ');
  return named ? message : name + ": " + message;
}

void rethrow_with_context(const std::string& name) {
  try {
    throw;
  } catch (const UsageError& e) {
    throw UsageError(with_context(name, e.what()));
  } catch (const ConfigError& e) {
    throw ConfigError(with_context(name, e.what()));
  } catch (const Error& e) {
    throw Error(with_context(name, e.what()));
  } catch (const std::bad_alloc&) {
    throw;  // out of memory: said as such by whoever catches it
  } catch (const std::exception& e) {
    // A plugin's std::out_of_range from .at() or an Eigen or standard
    // library failure: an Error, so that the message says whose it was.
    throw Error(with_context(name, e.what()));
  }
}

void rethrow_at(const SourceLocation& where, const std::string& label) {
  try {
    throw;
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    if (!where.file.empty() && message.compare(0, where.file.size(), where.file) == 0) throw;  // already placed
    if (dynamic_cast<const UsageError*>(&e)) throw UsageError(where, with_context(label, message));
    throw ConfigError(where, with_context(label, message));
  }
}

}  // namespace drape
