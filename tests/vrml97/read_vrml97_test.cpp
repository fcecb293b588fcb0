// The VRML97 / X3D classic reader: values, statements, errors, and the
// read -> write -> read round trip over the corpus.
#include "lodforge/io/vrml97/read_vrml97.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "vrml97/vrml97_corpus.h"

namespace lodforge::vrml97 {
namespace {

std::string error_of(std::string_view text) {
  try {
    read_vrml97(text, {.source_name = "t.wrl"});
  } catch (const ParseError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadVrml97, TypedFieldsChildrenAndSharing) {
  auto r = read_vrml97(R"(#VRML V2.0 utf8
DEF T Transform { translation 1 2 3 children [
  DEF S Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }
    geometry IndexedFaceSet { coord DEF C Coordinate { point [0 0 0, 1 0 0, 0 1 0] }
                              coordIndex [0 1 2 -1] solid FALSE } }
  Transform { children USE S }
] }
)");
  ASSERT_EQ(r.scene.roots.size(), 1u);
  const auto& t = *r.scene.roots[0];
  EXPECT_EQ(t.name, "T");
  ASSERT_NE(t.value("translation"), nullptr);
  EXPECT_EQ(t.value("translation")->floats, (std::vector<float>{1, 2, 3}));
  const auto* children = t.value("children");
  ASSERT_NE(children, nullptr);
  ASSERT_EQ(children->nodes.size(), 2u);
  const auto& shape = children->nodes[0];
  EXPECT_EQ(shape->type, "Shape");
  // The USE is the same node.
  EXPECT_EQ(children->nodes[1]->value("children")->nodes[0], shape);
  const auto& ifs = *shape->value("geometry")->nodes[0];
  EXPECT_EQ(ifs.value("coordIndex")->ints, (std::vector<std::int32_t>{0, 1, 2, -1}));
  EXPECT_EQ(ifs.value("solid")->ints, (std::vector<std::int32_t>{0}));
  EXPECT_EQ(ifs.value("coord")->nodes[0]->value("point")->floats.size(), 9u);
}

TEST(ReadVrml97, StatementsAndUnknownNodesAreKept) {
  const std::string text = R"(#X3D V3.2 utf8
PROFILE Interchange
COMPONENT Shaders:1
META "title" "a test"
PROTO Spinner [ field SFFloat speed 1 ] { Transform { children [] } }
DEF P Spinner { speed 2 }
DEF TS TimeSensor { cycleInterval 2 loop TRUE }
DEF S Script { inputOnly SFTime t outputOnly SFFloat v initializeOnly SFNode n USE TS
  url "ecmascript: function t() {}" }
ROUTE TS.time TO S.t
)";
  auto r = read_vrml97(text);
  ASSERT_EQ(r.scene.roots.size(), 8u);
  EXPECT_TRUE(r.scene.roots[0]->statement);
  EXPECT_EQ(r.scene.roots[0]->type, "PROFILE");
  EXPECT_EQ(r.scene.roots[0]->raw_body, "Interchange");
  EXPECT_EQ(r.scene.roots[1]->raw_body, "Shaders:1");
  EXPECT_EQ(r.scene.roots[2]->raw_body, R"("title" "a test")");
  EXPECT_EQ(r.scene.roots[3]->raw_body,
            "Spinner [ field SFFloat speed 1 ] { Transform { children [] } }");
  EXPECT_EQ(r.scene.roots[7]->raw_body, "TS.time TO S.t");
  const auto& script = *r.scene.roots[6];
  ASSERT_EQ(script.fields.size(), 4u);
  EXPECT_EQ(script.fields[0].name, "inputOnly SFTime t");
  EXPECT_TRUE(script.fields[0].no_value);
  EXPECT_EQ(script.fields[2].value.nodes.at(0), r.scene.roots[5]);
  // Written and read back: the same scene, and the statements as they were.
  const std::string written = write_vrml97(r.scene);
  EXPECT_NE(written.find("ROUTE TS.time TO S.t"), std::string::npos) << written;
  EXPECT_NE(written.find("PROFILE Interchange"), std::string::npos);
  EXPECT_TRUE(scene::equal(r.scene, read_vrml97(written).scene)) << written;
}

TEST(ReadVrml97, UntypedFieldsHoldNodesWhenTheyAreNodes) {
  auto r = read_vrml97(R"(#VRML V2.0 utf8
Collision { collide FALSE proxy DEF B Box { size 1 1 1 } children [ Shape { geometry USE B } ] }
Anchor { parameter [ "a=1" "b=2" ] url [ "a.wrl" "b.wrl" ] children [] }
)");
  const auto& c = *r.scene.roots[0];
  EXPECT_TRUE(c.fields[0].is_raw);
  EXPECT_EQ(c.fields[0].raw, "FALSE");
  EXPECT_EQ(c.fields[1].value.nodes.at(0)->type, "Box");
  EXPECT_EQ(c.value("children")->nodes.at(0)->value("geometry")->nodes.at(0),
            c.fields[1].value.nodes[0]);
  EXPECT_EQ(r.scene.roots[1]->fields[0].raw, R"([ "a=1" "b=2" ])");
  // File references are typed (so they can follow a scene written elsewhere).
  EXPECT_FALSE(r.scene.roots[1]->fields[1].is_raw);
  EXPECT_EQ(r.scene.roots[1]->fields[1].value.strings,
            (std::vector<std::string>{"a.wrl", "b.wrl"}));
}

TEST(ReadVrml97, ErrorsNameFileLineColumnAndWhatWasExpected) {
  EXPECT_EQ(error_of("#VRML V1.0 ascii\nSeparator {}"),
            "t.wrl:1:1: expected header '#VRML V2.0 utf8' or '#X3D V3.x utf8', got '#VRML V1.0 "
            "ascii'");
  EXPECT_EQ(error_of("#VRML V2.0 utf8\nShape { geometry USE Nope }"),
            "t.wrl:2:22: USE of undefined node name 'Nope'");
  EXPECT_EQ(error_of("#VRML V2.0 utf8\nTransform { translation 1 2 }"),
            "t.wrl:2:29: expected a number for SFVec3f field 'translation', got '}'");
  EXPECT_EQ(error_of("#VRML V2.0 utf8\nTransform { children [ 12 ] }"),
            "t.wrl:2:24: expected a node or ']' for field 'children', got '12'");
  EXPECT_NE(error_of("#VRML V2.0 utf8\nGroup { children [ Shape {} "), "");
  EXPECT_NE(error_of("#VRML V2.0 utf8\nROUTE a.b FROM c.d"), "");
}

std::string with_line_ends(std::string_view text, std::string_view end) {
  std::string out;
  for (char c : text) {
    if (c == '\n')
      out.append(end);
    else
      out.push_back(c);
  }
  return out;
}

std::string linefeeds_only(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\r')
      out.push_back(text[i]);
    else if (i + 1 == text.size() || text[i + 1] != '\n')
      out.push_back('\n');
  }
  return out;
}

// Old Mac files end their lines with a carriage return alone: the header and
// each comment stop there, and messages count those lines.
TEST(ReadVrml97, LinesEndAtCarriageReturnsAsWellAsLinefeeds) {
  using namespace std::string_literals;
  const auto files = testing::vrml97_corpus_files();
  ASSERT_FALSE(files.empty());
  const ReadResult lf = read_vrml97_file(files.front());
  const std::string written = write_vrml97(lf.scene);
  for (std::string_view end : {"\r", "\r\n"}) {
    const ReadResult other = read_vrml97(with_line_ends(written, end), {.source_name = "cr"});
    EXPECT_EQ(other.scene.header, lf.scene.header);
    // Statements kept as text (PROTO bodies) keep their line ends as read.
    EXPECT_EQ(linefeeds_only(write_vrml97(other.scene)), written) << files.front();
  }
  EXPECT_EQ(error_of("#VRML V2.0 utf8 # made on a Mac\r# a comment\rTransform { translation 1 2 }"),
            "t.wrl:3:29: expected a number for SFVec3f field 'translation', got '}'");
  // A header line holding control characters is written back as the header it was read as.
  const ReadResult odd = read_vrml97("#VRML V2.0 utf8\0\1 x\r\rGroup {}\r"s);
  EXPECT_EQ(odd.scene.header, "#VRML V2.0 utf8\0\1 x"s);
  ASSERT_EQ(odd.scene.roots.size(), 1u);
  EXPECT_EQ(read_vrml97(write_vrml97(odd.scene)).scene.header, odd.scene.header);
}

TEST(ReadVrml97, DeepNestingIsAnError) {
  std::string text = "#VRML V2.0 utf8\n";
  for (int i = 0; i < 300; ++i) text += "Group { children [ ";
  EXPECT_NE(error_of(text).find("nested deeper than 256"), std::string::npos);
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, WriteThenReadGivesTheSameScene) {
  ReadResult first = read_vrml97_file(GetParam());
  ASSERT_FALSE(first.scene.roots.empty()) << GetParam();
  const std::string text = write_vrml97(first.scene);
  ReadResult second = read_vrml97(text, {.source_name = "written"});
  EXPECT_TRUE(scene::equal(first.scene, second.scene)) << GetParam();
  EXPECT_EQ(text, write_vrml97(second.scene));
}

INSTANTIATE_TEST_SUITE_P(Corpus, RoundTrip, ::testing::ValuesIn(testing::vrml97_corpus_files()),
                         [](const auto& info) { return testing::corpus_test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RoundTrip);

TEST(RoundTripCorpus, CorpusIsPresent) {
  EXPECT_GE(testing::vrml97_corpus_files().size(), 40u)
      << "expected the corpus at " << LODFORGE_SHARED_DATA;
}

}  // namespace
}  // namespace lodforge::vrml97
