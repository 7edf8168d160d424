#pragma once
/// The campaign journal: every finished result is appended to OUTPUT.journal and flushed, so a
/// kill between two cube checkpoints loses nothing; on resume the cube is read and the journal's
/// valid records are replayed. After each cube checkpoint the journal starts over.
///
/// Format (host byte order): a header of magic "RIGIDJ03", the 64-character key (the campaign's
/// combined input digest) and a CRC-32 of both; then fixed-size records of a TaskResult (with
/// its failure message), an 8-byte fingerprint of the key and a CRC-32 (zlib) of both. Journals
/// of the previous format RIGIDJ02 (records without the message) are read too. Records are checked one by one: a
/// bad one is reported and skipped, the others kept; the fingerprint lets records be trusted
/// even when the header is damaged.
#include <cstdio>
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

 private:
  std::string path_, key_;
  std::FILE* file_ = nullptr;
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
