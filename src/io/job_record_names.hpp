#pragma once
// The names a job file's records get when it names none: the reader derives them, the writer
// leaves out a name that the reader would derive anyway.
#include <string>

namespace rigid::io {

/// A PEER set's name: its first file's stem without the -X of a set (RSN1_A-X.AT2 -> RSN1_A).
std::string record_name(const std::string& spec);
/// A lab recording's name: its file name without .gz and the text extension (Test013.txt.gz -> Test013).
std::string lab_record_name(const std::string& file);

}  // namespace rigid::io
