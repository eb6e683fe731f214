// Text files written whole or not at all.
#pragma once

#include <filesystem>
#include <string>

namespace tfmb {

// Writes `text` to `target` through a temporary file beside it, renamed into place once the
// write is known to have succeeded. A failed write (a full disk shows at close) removes the
// temporary and throws InternalError naming the file and the reason (exit 4): nothing partial
// is left, and an existing `target` stays as it was.
void write_text_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace tfmb
