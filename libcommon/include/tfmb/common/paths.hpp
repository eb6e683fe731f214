// Where the running program is, to find the data an installed tree keeps beside it.
#pragma once

#include <filesystem>

namespace tfmb {

// The running executable's path with symbolic links resolved (/proc/self/exe); empty if unknown.
std::filesystem::path executable_path();

// `relative` taken from the running executable's directory (e.g. "../share/tfmb/data/x.h5"
// from <prefix>/bin), normalised; empty if the executable's path is unknown or nothing is there.
std::filesystem::path beside_executable(const std::filesystem::path& relative);

}  // namespace tfmb
