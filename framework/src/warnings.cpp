// warn and set_warning_handler (warnings.hpp).
#include <drape/error_context.hpp>
#include <drape/warnings.hpp>

#include <iostream>
#include <mutex>

namespace drape {
namespace {

std::mutex& handler_mutex() {
  static std::mutex m;
  return m;
}

WarningHandler& current_handler() {
  static WarningHandler handler;
  return handler;
}

}  // namespace

void warn(const std::string& plain_text) {
  // A plugin's warning names the plugin (error_context.hpp).
  const std::string* context = current_context();
  const std::string text = context ? with_context(*context, plain_text) : plain_text;
  WarningHandler handler;
  {
    // Called outside the lock: a handler may wait for something (Python's
    // GIL) that another thread holds while it warns too.
    const std::lock_guard<std::mutex> lock(handler_mutex());
    handler = current_handler();
  }
  if (handler) {
    handler(text);
    return;
  }
  static std::mutex stderr_mutex;  // whole lines from several threads
  const std::lock_guard<std::mutex> lock(stderr_mutex);
  std::cerr << "drape: warning: " << text << "\n";
}

WarningHandler set_warning_handler(WarningHandler handler) {
  const std::lock_guard<std::mutex> lock(handler_mutex());
  WarningHandler previous = std::move(current_handler());
  current_handler() = std::move(handler);
  return previous;
}

}  // namespace drape
