// Parse -> write -> parse gives the same scene graph, for every file of the
// corpus and the examples, under every writer option combination.
#include <gtest/gtest.h>

#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "vrml1/corpus.h"

namespace lodforge::vrml1 {
namespace {

const std::vector<WriteOptions>& writer_variants() {
  static const std::vector<WriteOptions> v = {
      {},
      {.no_tabs = true},
      {.minimize = true},
      {.floats_per_line = 1, .ints_per_line = 1},
      {.floats_per_line = 100, .ints_per_line = 3, .no_tabs = true},
  };
  return v;
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, WriteThenReadGivesTheSameScene) {
  ReadResult first = read_vrml1_file(GetParam());
  ASSERT_FALSE(first.scene.roots.empty()) << GetParam();
  for (const auto& opt : writer_variants()) {
    std::string text = write_vrml1(first.scene, opt);
    ReadResult second = read_vrml1(text, {.source_name = "written"});
    EXPECT_TRUE(scene::equal(first.scene, second.scene))
        << GetParam() << " floats_per_line=" << opt.floats_per_line
        << " ints_per_line=" << opt.ints_per_line << " no_tabs=" << opt.no_tabs
        << " minimize=" << opt.minimize;
    // Writing is deterministic and stable: the second generation is the same text.
    EXPECT_EQ(text, write_vrml1(second.scene, opt));
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, RoundTrip,
                         ::testing::ValuesIn(lodforge::testing::all_vrml_test_files()),
                         [](const auto& info) {
                           return lodforge::testing::test_name_for(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RoundTrip);

TEST(RoundTripCorpus, CorpusIsPresent) {
  // CI has ../shared/data; without it the corpus tests above do not exist.
  auto files = lodforge::testing::all_vrml_test_files();
  EXPECT_GT(files.size(), 50u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
}

}  // namespace
}  // namespace lodforge::vrml1
