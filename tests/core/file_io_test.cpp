// write_file_atomic: the file appears whole or not at all, links stay links,
// a replaced file keeps its mode, and nodes that are not regular files are
// never replaced.
#include "lodforge/core/file_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "core/special_files.h"
#include "core/temp_dir.h"
#include "lodforge/core/error.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class WriteFileAtomic : public testing::TempDirTest {
 protected:
  static mode_t mode_of(const std::string& p) {
    struct stat st {};
    EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
    return st.st_mode & 07777;
  }
  // Names in the folder (temporary files left behind would show here).
  std::vector<std::string> listing(const std::string& sub = "") const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_ / sub))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

// A stream that inflates past its cap (a gzip bomb) is refused with the
// sizes; one within the cap reads back.
TEST(Gunzip, InflationIsCapped) {
  const std::string spaces(std::size_t{1} << 20, ' ');
  const std::string packed = gzip(spaces);  // about a thousand times smaller
  EXPECT_EQ(gunzip(packed, "s.gz", spaces.size()), spaces);
  try {
    gunzip(packed, "s.gz", spaces.size() - 1);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.gz: the gzip data inflates to more than 0 MiB"));
    EXPECT_THAT(e.what(), HasSubstr("refused as a possible gzip bomb"));
  }
  EXPECT_EQ(max_inflated_size(1000), std::size_t{64} << 20);
  EXPECT_EQ(max_inflated_size(std::size_t{10} << 20), std::size_t{640} << 20);
}

TEST_F(WriteFileAtomic, NewFileGetsTheUmaskModeAndNoTemporaryIsLeft) {
  const mode_t mask = ::umask(022);
  write_file_atomic(path("a.txt"), "hello");
  ::umask(mask);
  EXPECT_EQ(read_file(path("a.txt")), "hello");
  EXPECT_EQ(mode_of(path("a.txt")), 0644u);
  EXPECT_THAT(listing(), ::testing::ElementsAre("a.txt"));
}

TEST_F(WriteFileAtomic, AReplacedFileKeepsItsMode) {
  for (mode_t mode : {0600u, 0755u, 0640u}) {
    std::ofstream(path("a.txt")) << "old";
    fs::permissions(path("a.txt"), fs::perms(mode));
    write_file_atomic(path("a.txt"), "new");
    EXPECT_EQ(read_file(path("a.txt")), "new");
    EXPECT_EQ(mode_of(path("a.txt")), mode);
  }
}

TEST_F(WriteFileAtomic, ALinkStaysALinkAndItsTargetGetsTheContent) {
  fs::create_directory(path("real"));
  std::ofstream(path("real/target.txt")) << "old";
  fs::permissions(path("real/target.txt"), fs::perms(0600));
  fs::create_symlink("real/target.txt", path("link.txt"));
  write_file_atomic(path("link.txt"), "new");
  EXPECT_TRUE(fs::is_symlink(path("link.txt")));
  EXPECT_EQ(fs::read_symlink(path("link.txt")), fs::path("real/target.txt"));
  EXPECT_EQ(read_file(path("real/target.txt")), "new");
  EXPECT_EQ(mode_of(path("real/target.txt")), 0600u);
  // The temporary file was made beside the target, and is gone.
  EXPECT_THAT(listing(), ::testing::ElementsAre("link.txt", "real"));
  EXPECT_THAT(listing("real"), ::testing::ElementsAre("target.txt"));
  // A dangling link creates its target.
  fs::create_symlink("real/new.txt", path("dangling.txt"));
  write_file_atomic(path("dangling.txt"), "made");
  EXPECT_TRUE(fs::is_symlink(path("dangling.txt")));
  EXPECT_EQ(read_file(path("real/new.txt")), "made");
}

TEST_F(WriteFileAtomic, NodesThatAreNotRegularFilesAreRefusedAndStayWhatTheyWere) {
  for (test::Special kind : test::kRefusedKinds) {
    SCOPED_TRACE(test::kind_text(kind));
    const std::string p = path("node");
    if (!test::make_special(p, kind)) {
      // mknod needs privileges (the test runs have them as root); the other
      // kinds are still checked.
      ASSERT_EQ(kind, test::Special::kNullDevice) << "cannot make " << test::kind_text(kind);
      continue;
    }
    try {
      write_file_atomic(p, "data");  // a FIFO would block if it were opened
      ADD_FAILURE() << "written";
    } catch (const DataError& e) {
      EXPECT_THAT(e.what(), HasSubstr(p + ": is " + test::kind_text(kind)));
    }
    EXPECT_EQ(test::type_at(p), test::file_type_of(kind));
    EXPECT_THAT(listing(), ::testing::ElementsAre("node"));
    fs::remove(p);
  }
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

class FileBytesTest : public testing::TempDirTest {};

TEST_F(FileBytesTest, ARegularFileGivesItsBytes) {
  const std::string text = std::string("#VRML V1.0 ascii\n") + std::string(100000, 'x') + "\n";
  const std::string p = write("plain.wrl", text);
  const FileBytes bytes(p);
  EXPECT_EQ(bytes.view(), text);
  EXPECT_EQ(read_file(p), text);
}

TEST_F(FileBytesTest, GzipDataIsInflated) {
  const std::string text = "#VRML V1.0 ascii\nSeparator {}\n";
  const std::string p = write("packed.wrl.gz", gzip(text));
  EXPECT_EQ(FileBytes(p).view(), text);
}

TEST_F(FileBytesTest, TheHeadOfAFileIsItsFirstBytesInflated) {
  // A large stream: the head comes from its first bytes only.
  const std::string text = "#VRML V2.0 utf8\n" + std::string(5000000, ' ') + "Group {}\n";
  EXPECT_EQ(read_head(write("plain.wrl", text), 16), text.substr(0, 16));
  EXPECT_EQ(read_head(write("packed.wrl.gz", gzip(text)), 16), text.substr(0, 16));
  EXPECT_EQ(read_head(write("short.wrl", "#VRML"), 16), "#VRML");
  EXPECT_EQ(read_head(path("none.wrl"), 16), "");
  std::string corrupt = gzip(text);
  corrupt.resize(12);  // the header and nothing inflatable
  EXPECT_EQ(read_head(write("corrupt.wrl.gz", corrupt), 16), "");
}

TEST_F(FileBytesTest, AnEmptyFileIsEmpty) {
  EXPECT_TRUE(FileBytes(write("empty.wrl", "")).view().empty());
}

TEST_F(FileBytesTest, MissingFilesAndFoldersAreDataErrors) {
  EXPECT_THAT([&] { FileBytes b(path("none.wrl")); },
              ::testing::ThrowsMessage<DataError>(HasSubstr("cannot open")));
  fs::create_directories(path("folder"));
  EXPECT_THAT([&] { FileBytes b(path("folder")); },
              ::testing::ThrowsMessage<DataError>(HasSubstr("is a directory")));
}

TEST_F(FileBytesTest, AFifoIsReadThroughOnceNotMapped) {
  const std::string p = path("pipe");
  ASSERT_TRUE(test::make_special(p, test::Special::kFifo));
  const std::string text = "data through a pipe\n";
  std::thread writer([&] { std::ofstream(p) << text; });
  const FileBytes bytes(p);
  writer.join();
  EXPECT_EQ(bytes.view(), text);
}

}  // namespace
}  // namespace lodforge

namespace lodforge {
namespace {

class AtomicFileWriterTest : public testing::TempDirTest {};

TEST_F(AtomicFileWriterTest, PiecesMakeOneFileOnlyAtCommit) {
  const std::string p = write("out.wrl", "old content\n");
  {
    AtomicFileWriter out(p);
    for (int i = 0; i < 1000; ++i) out.write("piece " + std::to_string(i) + "\n");
    EXPECT_EQ(read_file(p), "old content\n") << "nothing replaced before commit";
    out.commit();
  }
  const std::string text = read_file(p);
  EXPECT_TRUE(text.starts_with("piece 0\npiece 1\n"));
  EXPECT_TRUE(text.ends_with("piece 999\n"));
  EXPECT_EQ(fs::directory_iterator(dir_)->path().filename(), "out.wrl") << "no temporary left";
}

TEST_F(AtomicFileWriterTest, WithoutCommitTheTargetStaysAndNoTemporaryIsLeft) {
  const std::string p = write("out.wrl", "old content\n");
  try {
    AtomicFileWriter out(p);
    out.write("half a scene");
    throw std::runtime_error("the writer fails on the way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read_file(p), "old content\n");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST_F(AtomicFileWriterTest, GzipInPiecesIsTheGzipOfTheWhole) {
  std::string whole;
  AtomicFileWriter out(path("big.wrl.gz"));
  for (int i = 0; i < 200000; ++i) {
    const std::string piece = std::to_string(i * 7919 % 10007) + (i % 9 ? " " : "\n");
    whole += piece;
    out.write(piece);
  }
  out.commit();
  EXPECT_EQ(read_file(path("big.wrl.gz")), whole);  // read_file inflates
  EXPECT_EQ(FileBytes(path("big.wrl.gz")).view(), whole);
}

class MappedRegion : public testing::TempDirTest {};

TEST_F(MappedRegion, GivesTheBytesOfTheRangeAtAnyOffset) {
  // Offsets off a page boundary and across one.
  std::string text(10000, '\0');
  for (std::size_t i = 0; i < text.size(); ++i) text[i] = static_cast<char>('a' + i % 26);
  const std::string p = write("r.bin", text);
  EXPECT_EQ(MappedFileRegion(p, 0, 3).view(), "abc");
  EXPECT_EQ(MappedFileRegion(p, 4095, 5).view(), text.substr(4095, 5));
  EXPECT_EQ(MappedFileRegion(p, 9990, 10).view(), text.substr(9990));
  EXPECT_EQ(MappedFileRegion(p, 10000, 0).view(), "");
}

TEST_F(MappedRegion, ShortFilesAndFoldersAreDataErrors) {
  const std::string p = write("r.bin", "0123456789");
  EXPECT_THAT([&] { MappedFileRegion(p, 4, 7); },
              ::testing::ThrowsMessage<DataError>(
                  HasSubstr("r.bin: expected 7 bytes from byte 4, the file has 10")));
  EXPECT_THROW(MappedFileRegion(dir_.string(), 0, 1), DataError);
  EXPECT_THROW(MappedFileRegion(path("missing"), 0, 1), DataError);
}

}  // namespace
}  // namespace lodforge
