#include "rigid/io/provenance.hpp"

#include <nettle/sha2.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

std::string hex(const std::uint8_t* d, std::size_t n) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s(2 * n, '0');
  for (std::size_t i = 0; i < n; ++i) {
    s[2 * i] = kDigits[d[i] >> 4];
    s[2 * i + 1] = kDigits[d[i] & 15];
  }
  return s;
}

std::string finish(sha256_ctx& ctx) {
  std::uint8_t digest[SHA256_DIGEST_SIZE];
  sha256_digest(&ctx, sizeof digest, digest);
  return hex(digest, sizeof digest);
}

}  // namespace

std::string sha256_hex(std::string_view data) {
  sha256_ctx ctx;
  sha256_init(&ctx);
  sha256_update(&ctx, data.size(), reinterpret_cast<const std::uint8_t*>(data.data()));
  return finish(ctx);
}

std::string file_sha256(const std::string& path) {
  std::error_code ec;
  // a FIFO or device would block or never end
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "not a regular file (cannot hash it)");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw InputError(path, 0, std::string("cannot open to hash it: ") + std::strerror(errno));
  sha256_ctx ctx;
  sha256_init(&ctx);
  std::uint8_t buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) sha256_update(&ctx, n, buf);
  if (std::ferror(f.get())) throw InputError(path, 0, std::string("read error while hashing: ") + std::strerror(errno));
  return finish(ctx);
}

Digests digest_files(const std::vector<std::string>& paths) {
  Digests d;
  d.reserve(paths.size());
  for (const std::string& p : paths) d.push_back({p, file_sha256(p)});
  return d;
}

std::string format_digests(const Digests& d) {
  std::string s;
  for (const FileDigest& f : d) s += f.sha256 + "  " + f.path + "\n";
  return s;
}

Digests parse_digests(std::string_view text) {
  Digests d;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    if (line.size() > 66 && line.substr(64, 2) == "  ")
      d.push_back({std::string(line.substr(66)), std::string(line.substr(0, 64))});
  }
  return d;
}

std::optional<std::string> first_changed(const Digests& then, const Digests& now) {
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (i >= then.size() || then[i].sha256 != now[i].sha256) return now[i].path;
  }
  if (then.size() > now.size()) return then[now.size()].path;
  return std::nullopt;
}

}  // namespace rigid::io
