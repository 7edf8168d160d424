#pragma once
/// The campaign journal, the campaign's durability layer: every finished result is appended to
/// OUTPUT.journal and flushed (a kill of the process loses nothing), and fsynced at every
/// checkpoint (a crash of the node loses at most one checkpoint interval); on resume the cube is
/// read and the journal's valid records are replayed. After each whole-cube rewrite (a
/// compaction, src/campaign/checkpointer.cpp) the journal starts over with what the cube lacks.
///
/// Format (host byte order): a header of magic "RIGIDJ04", the 64-character key (the campaign's
/// combined input digest) and a CRC-32 of both; then fixed-size records of a TaskResult (with
/// its failure message and count of unconverged contact solves), an 8-byte fingerprint of the key
/// and a CRC-32 (zlib) of both. Journals of the previous formats are read too: RIGIDJ03 (records
/// without the count, read as -1, not recorded) and RIGIDJ02 (without the message either). Records are checked one by
/// one: a bad one is reported and skipped, the others kept; the fingerprint lets records be trusted even when the
/// header is damaged.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "rigid/campaign/plan.hpp"

namespace rigid::campaign {

class Journal {
 public:
  /// Starts PATH anew for `key`, holding the `carried` results (those read from the old journal,
  /// not yet in a cube), written to PATH.tmp and renamed so a failure leaves the old one whole.
  /// Throws rigid::InputError(path, ...) on an I/O failure.
  Journal(std::string path, std::string key, const std::vector<TaskResult>& carried = {});
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Appends a result (buffered); throws rigid::InputError on an I/O failure.
  void append(const TaskResult& r);
  /// Hands the appended records to the kernel (survives a process kill); throws on failure.
  void flush();
  /// Replaces the journal by one holding only `kept` (after a cube checkpoint has been renamed
  /// into place), atomically like the constructor; throws on failure (the old journal stays).
  void reset(const std::vector<TaskResult>& kept = {});

  /// The same replacement in two steps, so that the bulk of the writing needs no lock:
  /// start_reset writes PATH.tmp with the header and `kept`, flushed and fsynced, without touching
  /// the journal in use (it may run on another thread while results are appended);
  /// finish_reset appends `more` (what arrived meanwhile, flushed to the kernel like any append,
  /// fsynced at the next sync) and renames PATH.tmp over PATH. Both throw on failure, removing
  /// PATH.tmp; the old journal stays.
  using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
  File start_reset(const std::vector<TaskResult>& kept) const;
  /// Appends more records to a journal from start_reset, flushed and fsynced (no lock needed
  /// either); throws on failure, removing PATH.tmp.
  void extend(File& fresh, const TaskResult* more, std::size_t count) const;
  /// Returns the replaced journal, still open: closing the last handle of a large unlinked file
  /// frees its blocks, which can take tens of ms, so a caller under a lock closes it after.
  File finish_reset(File fresh, const TaskResult* more, std::size_t count);

  /// Flushes the appended records to the kernel and returns a duplicate of the file's descriptor,
  /// so that the fsync (sync) can run without the lock that guards the journal; a reset meanwhile
  /// leaves the descriptor on the replaced file, which is harmless (the new journal was fsynced).
  int flush_and_duplicate();
  /// fsyncs and closes a descriptor from flush_and_duplicate; throws on failure.
  void sync(int fd) const;

  /// Bytes in the journal: header and records.
  std::uint64_t bytes() const { return bytes_; }
  /// Bytes of one record.
  static std::size_t record_bytes();

 private:
  std::string path_, key_;
  std::uint64_t print_ = 0;  // the key's fingerprint, in every record
  std::FILE* file_ = nullptr;
  std::uint64_t bytes_ = 0;
};

/// What a journal holds for one key.
struct JournalContents {
  std::vector<TaskResult> results;    ///< records that passed their checks, in file order
  std::vector<std::string> problems;  ///< one line each: damaged header, records skipped
  bool foreign = false;               ///< a sound header written for another key
};

/// Reads PATH (nothing when missing): records with a bad checksum, another key's fingerprint or
/// a task outside [0, tasks) are skipped and reported; a torn last record (a kill mid-write) is
/// dropped silently.
JournalContents read_journal(const std::string& path, const std::string& key, long tasks);

}  // namespace rigid::campaign
