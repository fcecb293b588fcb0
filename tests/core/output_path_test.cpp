// Which outputs a command may write: regular files and new paths only, links
// followed to their target, never an input, never one file or standard output
// twice.
#include "lodforge/core/output_path.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "core/special_files.h"
#include "core/temp_dir.h"
#include "lodforge/core/error.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputPaths : public testing::TempDirTest {
 protected:
  // The message check_output_paths throws, or "" when it accepts.
  static std::string refusal(std::initializer_list<OutputPath> outputs,
                             std::initializer_list<std::string> inputs) {
    try {
      check_output_paths(std::span(outputs.begin(), outputs.size()),
                         std::span(inputs.begin(), inputs.size()));
    } catch (const DataError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(OutputPaths, RegularFilesAndNewPathsAreWrittenWhereNamed) {
  write("old.obj", "x");
  EXPECT_EQ(resolve_output_path(path("old.obj")), fs::path(path("old.obj")));
  EXPECT_EQ(resolve_output_path(path("new.obj")), fs::path(path("new.obj")));
  EXPECT_EQ(resolve_output_path("relative.obj"), fs::path("relative.obj"));
}

TEST_F(OutputPaths, DevicesFifosSocketsAndDirectoriesAreRefusedUntouched) {
  for (test::Special kind : test::kRefusedKinds) {
    const std::string p = path("node");
    if (!test::make_special(p, kind)) {
      // mknod needs privileges (the test runs have them as root); the other
      // kinds are still checked.
      ASSERT_EQ(kind, test::Special::kNullDevice) << "cannot make " << test::kind_text(kind);
      continue;
    }
    SCOPED_TRACE(test::kind_text(kind));
    try {
      resolve_output_path(p);
      ADD_FAILURE() << "accepted";
    } catch (const DataError& e) {
      EXPECT_THAT(e.what(), HasSubstr(p + ": is " + test::kind_text(kind) +
                                      ", expected a regular file or a new path"));
    }
    EXPECT_EQ(test::type_at(p), test::file_type_of(kind));
    fs::remove(p);
  }
}

TEST_F(OutputPaths, LinksAreFollowedToTheFileTheyEndAt) {
  fs::create_directory(path("real"));
  write("real/target.obj", "x");
  // Relative targets are taken from the link's folder, through a chain.
  fs::create_symlink("real/target.obj", path("first.obj"));
  fs::create_symlink("first.obj", path("second.obj"));
  EXPECT_EQ(fs::weakly_canonical(resolve_output_path(path("second.obj"))),
            fs::weakly_canonical(path("real/target.obj")));
  // A dangling link: its target is the file to create.
  fs::create_symlink("real/new.obj", path("dangling.obj"));
  EXPECT_EQ(resolve_output_path(path("dangling.obj")), dir_ / "real/new.obj");
}

TEST_F(OutputPaths, LinksToRefusedKindsAndLoopsAreRefused) {
  ASSERT_TRUE(test::make_special(path("fifo"), test::Special::kFifo));
  fs::create_symlink("fifo", path("to_fifo.wrl"));
  try {
    resolve_output_path(path("to_fifo.wrl"));
    ADD_FAILURE() << "accepted";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path("to_fifo.wrl") + ": links to " + path("fifo") +
                                    ", a FIFO; expected a regular file or a new path"));
  }
  fs::create_symlink("loop_b", path("loop_a"));
  fs::create_symlink("loop_a", path("loop_b"));
  EXPECT_THROW(
      {
        try {
          resolve_output_path(path("loop_a"));
        } catch (const DataError& e) {
          EXPECT_THAT(e.what(), HasSubstr("too many levels of symbolic links"));
          throw;
        }
      },
      DataError);
}

TEST_F(OutputPaths, AnOutputThatIsAnInputIsRefusedNamingBoth) {
  const std::string cow = write("cow.obj", "x");
  EXPECT_EQ(refusal({{cow, "the simplified mesh"}}, {cow}),
            cow + ": the simplified mesh would overwrite the input " + cow);
  // Other spellings, a hard link and a symbolic link name the same file.
  fs::create_directory(path("sub"));
  fs::create_hard_link(cow, path("hard.obj"));
  fs::create_symlink("cow.obj", path("soft.obj"));
  for (const std::string& other :
       {path("./cow.obj"), path("sub/../cow.obj"), path("hard.obj"), path("soft.obj")}) {
    SCOPED_TRACE(other);
    EXPECT_THAT(refusal({{other}}, {cow}),
                HasSubstr("the output would overwrite the input " + cow));
    EXPECT_THAT(refusal({{cow}}, {other}), HasSubstr("would overwrite the input " + other));
  }
  // Relative against absolute.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  EXPECT_THAT(refusal({{"cow.obj"}}, {cow}), HasSubstr("cow.obj: the output would overwrite"));
  EXPECT_THAT(refusal({{"./new.obj"}}, {"new.obj"}), HasSubstr("would overwrite the input"));
  fs::current_path(cwd);
  // Standard input is no file; another file is no input.
  EXPECT_EQ(refusal({{"-"}, {path("other.obj")}}, {"-", cow}), "");
}

TEST_F(OutputPaths, TwoOutputsToOneFileOrToStandardOutputAreRefused) {
  EXPECT_EQ(refusal({{"-", "the LOD scene of x.wrl"}, {"-", "the statistics (--stats)"}}, {}),
            "standard output: the LOD scene of x.wrl and the statistics (--stats) would both be "
            "written to it");
  EXPECT_EQ(refusal({{path("dup/s.wrl"), "the LOD scene of d1/s.wrl"},
                     {path("dup/s.wrl"), "the LOD scene of d2/s.wrl"}},
                    {}),
            path("dup/s.wrl") +
                ": the LOD scene of d1/s.wrl and the LOD scene of d2/s.wrl would both be written "
                "to it");
  write("a.wrl", "x");
  fs::create_symlink("a.wrl", path("link.wrl"));
  EXPECT_THAT(refusal({{path("a.wrl")}, {path("link.wrl")}}, {}),
              HasSubstr("would both be written to it"));
  EXPECT_EQ(refusal({{path("a.wrl")}, {path("b.wrl")}, {"-"}}, {}), "");
}

}  // namespace
}  // namespace lodforge
