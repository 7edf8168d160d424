// SHA-256 of campaign inputs (io/provenance.hpp): the FIPS 180-2 test vectors, files read in
// blocks, sha256sum lines both ways, and which file changed.
#include "rigid/io/provenance.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

TEST(Provenance, Sha256MatchesFips180Vectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Provenance, FileHashReadsInBlocksAndRefusesNonFiles) {
  const std::string path = ::testing::TempDir() + "provenance_million_a.txt";
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string(1000000, 'a');  // more than one read block
  }
  // FIPS 180-2 vector: one million 'a'
  EXPECT_EQ(file_sha256(path), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  std::remove(path.c_str());
  EXPECT_THROW(file_sha256(path), InputError);
  EXPECT_THROW(file_sha256(::testing::TempDir()), InputError);  // a directory
}

TEST(Provenance, DigestLinesRoundTrip) {
  const Digests d{{"a b/scene.toml", std::string(64, '1')}, {"(settings)", std::string(64, '2')}};
  const std::string text = format_digests(d);
  EXPECT_EQ(text, std::string(64, '1') + "  a b/scene.toml\n" + std::string(64, '2') + "  (settings)\n");
  const Digests back = parse_digests(text);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].path, "a b/scene.toml");
  EXPECT_EQ(back[1].sha256, std::string(64, '2'));
  EXPECT_TRUE(parse_digests("not a digest line\n").empty());
}

TEST(Provenance, FirstChangedComparesByPosition) {
  const Digests then{{"/old/scene.toml", "s"}, {"/old/block.stl", "b"}};
  // the same contents under other paths (another working directory) have not changed
  EXPECT_FALSE(first_changed(then, {{"scene.toml", "s"}, {"block.stl", "b"}}));
  EXPECT_EQ(first_changed(then, {{"scene.toml", "s"}, {"block.stl", "B"}}), "block.stl");
  EXPECT_EQ(first_changed(then, {{"scene.toml", "s"}, {"block.stl", "b"}, {"state.toml", "t"}}), "state.toml");
  EXPECT_EQ(first_changed(then, {{"scene.toml", "s"}}), "/old/block.stl");
}

}  // namespace
}  // namespace rigid::io
