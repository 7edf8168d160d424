#pragma once
/// Content hashes of the files a campaign reads (SHA-256, from nettle), so a resume can prove that
/// its inputs are the ones the cube's results were computed from. Digest lists are stored as
/// sha256sum lines ("HEX  PATH"), which `sha256sum -c` can check by hand.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// One input file and the SHA-256 of its contents (64 lower-case hex digits).
struct FileDigest {
  std::string path;
  std::string sha256;
};
using Digests = std::vector<FileDigest>;

/// SHA-256 of bytes, as 64 lower-case hex digits.
std::string sha256_hex(std::string_view data);

/// SHA-256 of a regular file's contents, read in blocks (bounded memory). Throws
/// rigid::InputError(path, ...) when it cannot be read or is not a regular file.
std::string file_sha256(const std::string& path);

/// Digests of files, in the given order.
Digests digest_files(const std::vector<std::string>& paths);

/// sha256sum lines, "HEX  PATH\n" each; parse_digests reads them back (malformed lines skipped).
std::string format_digests(const Digests& d);
Digests parse_digests(std::string_view text);

/// The first file whose contents differ between two digest lists of the same inputs, compared by
/// position (paths may be spelled differently from another directory): the path from `now`, or
/// from `then` for a file no longer read; nothing when the lists agree.
std::optional<std::string> first_changed(const Digests& then, const Digests& now);

}  // namespace rigid::io
