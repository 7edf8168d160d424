#include "rigid/campaign/journal.hpp"

#include <array>
#include <cstring>
#include <unistd.h>

#include "rigid/core/error.hpp"

namespace rigid::campaign {
namespace {

constexpr char kMagic[8] = {'R', 'I', 'G', 'I', 'D', 'J', '0', '1'};
constexpr std::size_t kHashBytes = 32;

std::uint32_t crc32(const unsigned char* data, std::size_t n) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::array<char, kHashBytes> padded(const std::string& hash) {
  std::array<char, kHashBytes> h{};
  std::memcpy(h.data(), hash.data(), std::min(hash.size(), kHashBytes));
  return h;
}

bool header_matches(std::FILE* f, const std::string& hash) {
  char magic[8];
  std::array<char, kHashBytes> h{};
  if (std::fread(magic, 1, 8, f) != 8 || std::memcmp(magic, kMagic, 8) != 0) return false;
  if (std::fread(h.data(), 1, kHashBytes, f) != kHashBytes) return false;
  return h == padded(hash);
}

}  // namespace

Journal::Journal(std::string path, std::string job_hash) : path_(std::move(path)), hash_(std::move(job_hash)) {
  std::FILE* existing = std::fopen(path_.c_str(), "rb");
  const bool reuse = existing && header_matches(existing, hash_);
  if (existing) std::fclose(existing);
  if (reuse) {
    file_ = std::fopen(path_.c_str(), "ab");
    if (!file_) throw InputError(path_, 0, "cannot append to the journal");
  } else {
    start_new();
  }
}

Journal::~Journal() {
  if (file_) std::fclose(file_);
}

void Journal::start_new() {
  if (file_) std::fclose(file_);
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw InputError(path_, 0, "cannot create the journal");
  const auto h = padded(hash_);
  std::fwrite(kMagic, 1, 8, file_);
  std::fwrite(h.data(), 1, kHashBytes, file_);
  flush();
}

void Journal::append(const TaskResult& r) {
  unsigned char buf[sizeof(TaskResult) + 4];
  std::memcpy(buf, &r, sizeof(TaskResult));
  const std::uint32_t c = crc32(buf, sizeof(TaskResult));
  std::memcpy(buf + sizeof(TaskResult), &c, 4);
  if (std::fwrite(buf, 1, sizeof buf, file_) != sizeof buf) throw InputError(path_, 0, "journal write failed");
}

void Journal::flush() {
  if (std::fflush(file_) != 0) throw InputError(path_, 0, "journal flush failed");
}

void Journal::reset() { start_new(); }

std::vector<TaskResult> read_journal(const std::string& path, const std::string& job_hash) {
  std::vector<TaskResult> out;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return out;
  if (header_matches(f, job_hash)) {
    unsigned char buf[sizeof(TaskResult) + 4];
    while (std::fread(buf, 1, sizeof buf, f) == sizeof buf) {
      std::uint32_t c;
      std::memcpy(&c, buf + sizeof(TaskResult), 4);
      if (c != crc32(buf, sizeof(TaskResult))) break;  // torn or corrupt: stop here
      TaskResult r;
      std::memcpy(&r, buf, sizeof(TaskResult));
      out.push_back(r);
    }
  }
  std::fclose(f);
  return out;
}

}  // namespace rigid::campaign
