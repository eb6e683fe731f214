// SHA-256 of files, recorded in /provenance so a reader can tell which inputs made a file.
#pragma once

#include <filesystem>
#include <string>

namespace tfmb {

// Lower-case hex SHA-256 of a file's bytes. Throws BadInput if the file cannot be read.
std::string sha256_file(const std::filesystem::path& file);
// Lower-case hex SHA-256 of a string.
std::string sha256_text(const std::string& text);

}  // namespace tfmb
