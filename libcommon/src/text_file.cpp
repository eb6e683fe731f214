#include "tfmb/common/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "tfmb/common/errors.hpp"

namespace tfmb {

void write_text_atomically(const std::filesystem::path& target, const std::string& text) {
  std::filesystem::path tmp = target;
  tmp += ".tmp";
  errno = 0;
  std::ofstream out(tmp);
  out << text;
  // A full disk shows when the buffer is written out, at close: checked there, and the partial
  // temporary file removed.
  out.close();
  std::error_code ec;
  if (!out) {
    const std::string reason = errno ? std::strerror(errno) : "write failed";
    std::filesystem::remove(tmp, ec);
    throw InternalError(target.string() + ": cannot write (" + reason + ")");
  }
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(tmp, ec);
    throw InternalError(target.string() + ": cannot rename from " + tmp.string() + " (" + reason +
                        ")");
  }
}

}  // namespace tfmb
