#pragma once
// One channel for warnings of the framework and the plugins: warn(text). The
// drape program prints each as "drape: warning: <text>" on stderr (the
// default handler); the Python module turns each into a Python warning
// (drape.DrapeWarning, a UserWarning), so `warnings.filterwarnings` and
// pytest see them. Thread-safe; the handler may be called from any thread.
#include <functional>
#include <string>

namespace drape {

using WarningHandler = std::function<void(const std::string& text)>;

// `text` is one sentence without a "warning: " prefix. Given inside a call the
// framework makes into a plugin, it gets the plugin's name in front
// ("bending: skipped 3 of 5,000 hinges ...", error_context.hpp).
void warn(const std::string& text);

// Replaces the handler (empty: the default, stderr) and returns the previous one.
WarningHandler set_warning_handler(WarningHandler handler);

}  // namespace drape
