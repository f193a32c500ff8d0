#include "facectl/face/file_digest.hpp"

#include <openssl/evp.h>

#include <cstdio>
#include <memory>
#include <string_view>

#include "facectl/face/input_error.hpp"

namespace facectl::face {

std::string sha256_file_hex(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"),
                                                          &std::fclose);
  if (!f) throw InputError(path + ": cannot open file");
  const std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw InputError(path + ": cannot start a SHA-256 digest");
  unsigned char buf[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0)
    if (EVP_DigestUpdate(ctx.get(), buf, n) != 1) throw InputError(path + ": SHA-256 failed");
  if (std::ferror(f.get())) throw InputError(path + ": read failed");
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (EVP_DigestFinal_ex(ctx.get(), md, &len) != 1) throw InputError(path + ": SHA-256 failed");
  constexpr std::string_view hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < len; ++i) {
    out += hex[md[i] >> 4];
    out += hex[md[i] & 15];
  }
  return out;
}

std::vector<std::array<std::string, 2>> head_file_digests(const HeadSpec& head) {
  std::vector<std::array<std::string, 2>> out;
  for (const std::string& f : head.files) out.push_back({f, sha256_file_hex(head.dir + "/" + f)});
  return out;
}

}  // namespace facectl::face
