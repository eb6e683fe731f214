#include "tfmb/common/hash.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

#include "tfmb/common/errors.hpp"

namespace tfmb {
namespace {
struct DigestContext {
  EVP_MD_CTX* context = EVP_MD_CTX_new();
  DigestContext() { EVP_DigestInit_ex(context, EVP_sha256(), nullptr); }
  ~DigestContext() { EVP_MD_CTX_free(context); }
  void update(const char* data, std::size_t size) { EVP_DigestUpdate(context, data, size); }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    EVP_DigestFinal_ex(context, digest.data(), &length);
    static const char* digits = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += digits[digest[i] >> 4];
      out += digits[digest[i] & 15];
    }
    return out;
  }
};
}  // namespace

std::string sha256_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw BadInput(file.string() + ": cannot read file");
  DigestContext digest;
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    digest.update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  return digest.hex();
}

std::string sha256_text(const std::string& text) {
  DigestContext digest;
  digest.update(text.data(), text.size());
  return digest.hex();
}

}  // namespace tfmb
