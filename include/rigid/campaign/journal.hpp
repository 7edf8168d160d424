#pragma once
/// The campaign journal: every finished result is appended to OUTPUT.journal (fixed-size
/// records, each with a CRC-32) and flushed, so a kill between two cube checkpoints loses
/// nothing; on resume the cube is read and the journal's valid records are replayed (a torn
/// last record is ignored). After each cube checkpoint the journal starts over.
#include <cstdio>
#include <string>
#include <vector>

#include "rigid/campaign/plan.hpp"

namespace rigid::campaign {

class Journal {
 public:
  /// Opens PATH for appending; a missing or foreign journal (other job hash) is started anew.
  Journal(std::string path, std::string job_hash);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  void append(const TaskResult& r);
  /// Hands the appended records to the kernel (survives a process kill).
  void flush();
  /// Empties the journal (after a cube checkpoint has been renamed into place).
  void reset();

 private:
  void start_new();
  std::string path_, hash_;
  std::FILE* file_ = nullptr;
};

/// Valid records of a journal written for job_hash (none if the file is missing or foreign).
std::vector<TaskResult> read_journal(const std::string& path, const std::string& job_hash);

}  // namespace rigid::campaign
