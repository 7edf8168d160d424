#include "rigid/campaign/journal.hpp"

#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "rigid/core/error.hpp"

namespace rigid::campaign {
namespace {

// A journal format: its magic and how many bytes of each TaskResult a record stores.
struct Format {
  char magic[8];
  std::size_t result_bytes;
  constexpr std::size_t record_bytes() const { return result_bytes + 8 + 4; }
};
// RIGIDJ04 carries the count of unconverged contact solves; the older formats store a prefix of
// TaskResult and are still read (the fields they lack keep their defaults: no message, count -1 =
// not recorded), so a resume across an upgrade keeps every journalled result.
constexpr Format kCurrent{{'R', 'I', 'G', 'I', 'D', 'J', '0', '4'}, sizeof(TaskResult)};
constexpr Format kWithoutSolverCount{{'R', 'I', 'G', 'I', 'D', 'J', '0', '3'}, offsetof(TaskResult, unconverged_steps)};
constexpr Format kWithoutMessages{{'R', 'I', 'G', 'I', 'D', 'J', '0', '2'}, offsetof(TaskResult, message)};
constexpr char kOldMagic[8] = {'R', 'I', 'G', 'I', 'D', 'J', '0', '1'};
constexpr std::size_t kKeyBytes = 64;
constexpr std::size_t kHeaderBytes = sizeof kCurrent.magic + kKeyBytes + 4;
constexpr std::size_t kRecordBytes = kCurrent.record_bytes();

std::uint32_t crc(const unsigned char* data, std::size_t n) {
  return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), data, static_cast<uInt>(n)));
}

std::string padded_key(const std::string& key) {
  std::string k = key.substr(0, kKeyBytes);
  k.resize(kKeyBytes, '\0');
  return k;
}

// 8 bytes that tie a record to its key: a CRC-64-sized slice of the key's own digest
std::uint64_t fingerprint(const std::string& key) {
  const std::string k = padded_key(key);
  const auto* p = reinterpret_cast<const unsigned char*>(k.data());
  return (std::uint64_t{crc(p, 32)} << 32) | crc(p + 32, 32);
}

void encode_header(unsigned char* out, const std::string& key, const Format& format = kCurrent) {
  std::memcpy(out, format.magic, sizeof format.magic);
  std::memcpy(out + sizeof format.magic, padded_key(key).data(), kKeyBytes);
  const std::uint32_t c = crc(out, kHeaderBytes - 4);
  std::memcpy(out + kHeaderBytes - 4, &c, 4);
}

void encode_record(unsigned char* out, const TaskResult& r, std::uint64_t print) {
  std::memcpy(out, &r, sizeof(TaskResult));
  std::memcpy(out + sizeof(TaskResult), &print, 8);
  const std::uint32_t c = crc(out, kRecordBytes - 4);
  std::memcpy(out + kRecordBytes - 4, &c, 4);
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(path, 0, what + ": " + std::strerror(errno));
}

// Writes COUNT records; false at the first failed write.
bool write_records(std::FILE* f, const TaskResult* records, std::size_t count, std::uint64_t print) {
  unsigned char buf[kRecordBytes];
  for (std::size_t i = 0; i < count; ++i) {
    encode_record(buf, records[i], print);
    if (std::fwrite(buf, 1, sizeof buf, f) != sizeof buf) return false;
  }
  return true;
}

// A failed replacement: closes and removes PATH.tmp and throws with the write's errno; the
// journal in use stays.
[[noreturn]] void abandon_reset(Journal::File& fresh, const std::string& path) {
  const int e = errno;
  fresh.reset();
  std::remove((path + ".tmp").c_str());
  errno = e;
  fail(path, "journal write failed");
}

}  // namespace

Journal::Journal(std::string path, std::string key, const std::vector<TaskResult>& carried)
    : path_(std::move(path)), key_(std::move(key)), print_(fingerprint(key_)) {
  reset(carried);
}

Journal::~Journal() {
  if (file_) std::fclose(file_);
}

std::size_t Journal::record_bytes() { return kRecordBytes; }

Journal::File Journal::start_reset(const std::vector<TaskResult>& kept) const {
  // written beside and renamed over, so the old journal stays whole until the new one is
  const std::string tmp = path_ + ".tmp";
  File f(std::fopen(tmp.c_str(), "wb"), std::fclose);
  if (!f) fail(path_, "cannot create " + tmp);
  unsigned char header[kHeaderBytes];
  encode_header(header, key_);
  const bool ok = std::fwrite(header, 1, sizeof header, f.get()) == sizeof header &&
                  write_records(f.get(), kept.data(), kept.size(), print_) && std::fflush(f.get()) == 0 &&
                  ::fsync(fileno(f.get())) == 0;
  if (!ok) abandon_reset(f, path_);
  return f;
}

void Journal::extend(File& fresh, const TaskResult* more, std::size_t count) const {
  const bool ok = write_records(fresh.get(), more, count, print_) && std::fflush(fresh.get()) == 0 &&
                  ::fsync(fileno(fresh.get())) == 0;
  if (!ok) abandon_reset(fresh, path_);
}

Journal::File Journal::finish_reset(File fresh, const TaskResult* more, std::size_t count) {
  const std::string tmp = path_ + ".tmp";
  const bool ok = write_records(fresh.get(), more, count, print_) && std::fflush(fresh.get()) == 0 &&
                  std::rename(tmp.c_str(), path_.c_str()) == 0;
  if (!ok) abandon_reset(fresh, path_);
  File old(file_, std::fclose);
  file_ = fresh.release();  // the renamed file, open for appending at its end
  bytes_ = std::uint64_t(std::ftell(file_));
  return old;
}

void Journal::reset(const std::vector<TaskResult>& kept) { finish_reset(start_reset(kept), nullptr, 0); }

void Journal::append(const TaskResult& r) {
  unsigned char buf[kRecordBytes];
  encode_record(buf, r, print_);
  if (std::fwrite(buf, 1, sizeof buf, file_) != sizeof buf) fail(path_, "journal write failed");
  bytes_ += kRecordBytes;
}

void Journal::flush() {
  if (std::fflush(file_) != 0) fail(path_, "journal write failed");
}

int Journal::flush_and_duplicate() {
  flush();
  const int fd = ::dup(fileno(file_));
  if (fd < 0) fail(path_, "journal sync failed");
  return fd;
}

void Journal::sync(int fd) const {
  const bool ok = ::fsync(fd) == 0;
  const int e = errno;
  ::close(fd);
  errno = e;
  if (!ok) fail(path_, "journal write failed");
}

JournalContents read_journal(const std::string& path, const std::string& key, long tasks) {
  JournalContents out;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) return out;
  unsigned char header[kHeaderBytes];
  const std::size_t got = std::fread(header, 1, sizeof header, f.get());
  if (got >= sizeof kOldMagic && std::memcmp(header, kOldMagic, sizeof kOldMagic) == 0) {
    out.problems.push_back(path + ": written by an earlier Rigid (format RIGIDJ01); its cells are simulated again");
    return out;
  }
  if (got < sizeof header) return out;  // killed while the header was written: nothing in it
  // the format by its magic; a damaged header is read as the current one
  const Format* format = &kCurrent;
  for (const Format* older : {&kWithoutSolverCount, &kWithoutMessages}) {
    if (std::memcmp(header, older->magic, sizeof older->magic) == 0) format = older;
  }
  unsigned char expected[kHeaderBytes];
  encode_header(expected, key, *format);
  std::uint32_t stored;
  std::memcpy(&stored, header + kHeaderBytes - 4, 4);
  if (stored != crc(header, kHeaderBytes - 4)) {
    out.problems.push_back(path + ": damaged header (bad checksum); its records are checked one by one");
  } else if (std::memcmp(header, expected, kHeaderBytes) != 0) {
    out.foreign = true;
    return out;
  }
  const std::uint64_t print = fingerprint(key);
  const std::size_t record_bytes = format->record_bytes();
  std::vector<unsigned char> buf(record_bytes);
  long index = 0, skipped = 0;
  for (; std::fread(buf.data(), 1, record_bytes, f.get()) == record_bytes; ++index) {
    std::uint32_t c;
    std::uint64_t p;
    TaskResult r;
    std::memcpy(&c, buf.data() + record_bytes - 4, 4);
    std::memcpy(&p, buf.data() + format->result_bytes, 8);
    std::memcpy(&r, buf.data(), format->result_bytes);
    std::string why;
    if (c != crc(buf.data(), record_bytes - 4)) {
      why = "bad checksum";
    } else if (p != print) {
      why = "written for other inputs";
    } else if (r.task < 0 || r.task >= tasks) {
      why = "task " + std::to_string(r.task) + " out of range";
    } else {
      r.message[kTaskMessageBytes - 1] = '\0';  // a message is text whatever the file holds
      out.results.push_back(r);
      continue;
    }
    // one line per bad record, up to a few; a summary beyond
    if (++skipped <= 5) {
      out.problems.push_back(path + ": record " + std::to_string(index) + " (byte " +
                             std::to_string(kHeaderBytes + std::size_t(index) * record_bytes) + "): " + why +
                             ", skipped (its cell is simulated again)");
    }
  }
  if (skipped > 5) out.problems.push_back(path + ": " + std::to_string(skipped - 5) + " more bad records skipped");
  return out;
}

}  // namespace rigid::campaign
