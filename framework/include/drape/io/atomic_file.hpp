#pragma once
// Outputs are written atomically: to a temporary file next to the target, then
// renamed over it, so a crash or kill never leaves a half-written file behind.
#include <filesystem>
#include <functional>
#include <string>

namespace drape {

// Calls write(tmp_path), then renames tmp_path to `target`. If write throws,
// the temporary file is removed and the exception propagates; `target` is untouched.
// The temporary lives in the same directory (rename is atomic only within a filesystem).
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// A text file (reports, pictures), atomically; Error when it cannot be written.
void write_text_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace drape
