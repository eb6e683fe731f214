#include "tfmb/common/paths.hpp"

#include <system_error>

namespace tfmb {

std::filesystem::path executable_path() {
  std::error_code error;
  auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path{} : path;
}

std::filesystem::path beside_executable(const std::filesystem::path& relative) {
  const auto executable = executable_path();
  if (executable.empty())
    return {};
  const auto candidate = (executable.parent_path() / relative).lexically_normal();
  std::error_code error;
  return std::filesystem::exists(candidate, error) ? candidate : std::filesystem::path{};
}

}  // namespace tfmb
