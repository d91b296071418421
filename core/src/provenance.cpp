#include "dtwire/core/provenance.hpp"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <unistd.h>

#include "dtwire/core/error.hpp"
#include "dtwire/version.hpp"

namespace dtwire {
namespace {
class Sha256 {
 public:
  Sha256() : context_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1)
      throw std::runtime_error("SHA-256 initialisation failed");
  }
  void update(const char* data, std::size_t size) { EVP_DigestUpdate(context_.get(), data, size); }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    EVP_DigestFinal_ex(context_.get(), digest.data(), &length);
    static const char* digits = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += digits[digest[i] >> 4];
      out += digits[digest[i] & 0xf];
    }
    return out;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context_;
};
}  // namespace

std::string sha256_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    throw InputError(path.string(), "cannot read file to hash it");
  Sha256 hash;
  std::array<char, 1 << 16> buffer{};
  while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0)
    hash.update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  return hash.hex();
}

std::string sha256_text(const std::string& text) {
  Sha256 hash;
  hash.update(text.data(), text.size());
  return hash.hex();
}

namespace {
std::string utc_now(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, format, &utc);
  return buffer;
}
}  // namespace

std::string utc_now_iso8601() { return utc_now("%Y-%m-%dT%H:%M:%SZ"); }

void Provenance::add_input(const std::filesystem::path& path) {
  input_sha256.emplace_back(path.string(), sha256_file(path));
}

std::string new_run_id() {
  std::random_device entropy;
  char random_text[16];
  std::snprintf(random_text, sizeof random_text, "%08x", static_cast<unsigned>(entropy()));
  return utc_now("%Y%m%dT%H%M%SZ") + "-" + std::to_string(::getpid()) + "-" + random_text;
}

const char* tool_version() { return kVersion; }
const char* git_hash() { return kGitHash; }

Provenance make_provenance(const std::string& command,
                           const std::vector<std::filesystem::path>& inputs) {
  Provenance p{tool_version(), git_hash(), utc_now_iso8601(), command, new_run_id(), {}};
  for (const auto& input : inputs) p.add_input(input);
  return p;
}

}  // namespace dtwire
