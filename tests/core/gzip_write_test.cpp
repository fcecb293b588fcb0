// Whole-file reading and atomic writing, with gzip both ways.
#include "lodforge/core/file_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/temp_dir.h"
#include "lodforge/core/error.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

std::string raw_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

class FileIo : public testing::TempDirTest {
 protected:
};

TEST(Gzip, RoundTripsEmptySmallAndLargeData) {
  std::mt19937 rng(7);
  std::string noisy(3 << 20, '\0');  // incompressible: the output outgrows the input
  for (char& c : noisy) c = static_cast<char>(rng());
  for (const std::string& data :
       {std::string(), std::string("#VRML V1.0 ascii\n"), std::string(1 << 20, 'a'), noisy}) {
    std::string z = gzip(data);
    EXPECT_TRUE(is_gzip(z));
    EXPECT_EQ(gunzip(z, "test"), data);
  }
  // Deterministic: no time stamp in the header.
  EXPECT_EQ(gzip("same"), gzip("same"));
}

TEST(Gzip, NamesEndingInGz) {
  EXPECT_TRUE(is_gzip_path("a.wrl.gz"));
  EXPECT_TRUE(is_gzip_path("dir/A.PLY.GZ"));
  EXPECT_TRUE(is_gzip_path(".gz"));
  EXPECT_FALSE(is_gzip_path("a.wrl"));
  EXPECT_FALSE(is_gzip_path("a.tgz"));
  EXPECT_FALSE(is_gzip_path("gz"));
  EXPECT_FALSE(is_gzip_path("-"));
}

TEST_F(FileIo, GzTargetIsWrittenCompressedAndReadBack) {
  const std::string text = "ply\nformat ascii 1.0\nend_header\n" + std::string(10000, '0');
  fs::path target = dir_ / "x.ply.gz";
  write_file_atomic(target.string(), text);
  std::string bytes = raw_bytes(target);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
  EXPECT_LT(bytes.size(), text.size());
  EXPECT_EQ(read_file(target.string()), text);
  // Replacing it leaves only the target (no temporary file).
  write_file_atomic(target.string(), "again");
  EXPECT_EQ(read_file(target.string()), "again");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(FileIo, OtherNamesAreWrittenAsGiven) {
  fs::path target = dir_ / "x.gzip";
  write_file_atomic(target.string(), "plain");
  EXPECT_EQ(raw_bytes(target), "plain");
}

TEST_F(FileIo, MissingFolderIsAnErrorWithoutFile) {
  fs::path target = dir_ / "missing" / "x.wrl.gz";
  EXPECT_THROW(write_file_atomic(target.string(), "x"), DataError);
  EXPECT_FALSE(fs::exists(target));
}

}  // namespace
}  // namespace lodforge
