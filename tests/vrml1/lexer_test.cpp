// The VRML 1.0 lexer: tokens with their positions, comments, numbers, node
// bodies skipped whole, and the parser's shared helpers.
#include "lodforge/io/vrml1/lexer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <unordered_map>
#include <vector>

#include "lodforge/core/error.h"

namespace lodforge::vrml1::detail {
namespace {

using ::testing::ThrowsMessage;

TEST(Lexer, TokensCarryTheirKindTextLineAndColumn) {
  Lexer lex("Separator {  # a comment { [\n  DEF A Cube { size 1,2 }\n \"a \\\"b\\\"\" | ( ) ] }",
            "t.wrl");
  struct Seen {
    TokenKind kind;
    std::string text;
    int line, col;
  };
  std::vector<Seen> seen;
  for (Token t = lex.next(); t.kind != TokenKind::kEnd; t = lex.next())
    seen.push_back({t.kind, std::string(t.text), t.line, t.col});
  const std::vector<std::pair<TokenKind, std::string>> expected = {
      {TokenKind::kWord, "Separator"}, {TokenKind::kLBrace, "{"},
      {TokenKind::kWord, "DEF"},       {TokenKind::kWord, "A"},
      {TokenKind::kWord, "Cube"},      {TokenKind::kLBrace, "{"},
      {TokenKind::kWord, "size"},      {TokenKind::kWord, "1"},
      {TokenKind::kComma, ","},        {TokenKind::kWord, "2"},
      {TokenKind::kRBrace, "}"},       {TokenKind::kString, "\"a \\\"b\\\"\""},
      {TokenKind::kBar, "|"},          {TokenKind::kLParen, "("},
      {TokenKind::kRParen, ")"},       {TokenKind::kRBracket, "]"},
      {TokenKind::kRBrace, "}"}};
  ASSERT_EQ(seen.size(), expected.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].kind, expected[i].first) << i;
    EXPECT_EQ(seen[i].text, expected[i].second) << i;
  }
  EXPECT_EQ(seen[2].line, 2);  // DEF, after the comment's line
  EXPECT_EQ(seen[2].col, 3);
  EXPECT_EQ(seen[11].line, 3);
  EXPECT_EQ(unquote(seen[11].text), "a \"b\"");
}

TEST(Lexer, PeekDoesNotConsumeAndNumbersReadInPlace) {
  Lexer lex("  1.5e1, -3 ,7 word", "t");
  EXPECT_EQ(lex.peek().text, "1.5e1");
  float f = 0;
  ASSERT_TRUE(lex.read_float(f, true));  // after a peek, from the same place
  EXPECT_EQ(f, 15.f);
  std::int32_t i = 0;
  ASSERT_TRUE(lex.read_int(i, true));
  EXPECT_EQ(i, -3);
  ASSERT_TRUE(lex.read_int(i, true));
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(lex.read_float(f, true));  // a word: nothing consumed
  EXPECT_EQ(lex.next().text, "word");
  EXPECT_EQ(lex.next().kind, TokenKind::kEnd);
}

TEST(Lexer, SkipBalancedBodyHonoursNestingStringsAndComments) {
  Lexer lex("Unknown { a { b \"}\" } # }\n c } Cube {}", "t");
  lex.next();
  const Token open = lex.next();
  EXPECT_EQ(lex.skip_balanced_body(open), " a { b \"}\" } # }\n c ");
  EXPECT_EQ(lex.next().kind, TokenKind::kRBrace);
  EXPECT_EQ(lex.next().text, "Cube");
  Lexer open_ended("X { { }", "u.wrl");
  open_ended.next();
  const Token brace = open_ended.next();
  EXPECT_THROW(open_ended.skip_balanced_body(brace), ParseError);
}

TEST(Lexer, HelpersReadNodeStartsAndNameWhatIsWrong) {
  const std::unordered_map<std::string, scene::NodePtr> defs = {{"Box", scene::make_node("Cube")}};
  Lexer lex("DEF Ball Sphere { } USE Box USE Nothing DEF X USE", "t.wrl");
  NodeStart s = read_node_start(lex, defs, lex.next());
  EXPECT_EQ(s.def_name, "Ball");
  EXPECT_EQ(s.type.text, "Sphere");
  Token open;
  EXPECT_EQ(open_node(lex, s.type, open)->type, "Sphere");
  EXPECT_EQ(open.kind, TokenKind::kLBrace);
  lex.next();  // }
  s = read_node_start(lex, defs, lex.next());
  EXPECT_EQ(s.used, defs.at("Box"));
  const Token use = lex.next();
  EXPECT_THAT(
      [&] { read_node_start(lex, defs, use); },
      ThrowsMessage<ParseError>(::testing::HasSubstr("USE of undefined node name 'Nothing'")));
  EXPECT_THAT([&] { read_node_start(lex, defs, lex.next()); },
              ThrowsMessage<ParseError>(
                  ::testing::HasSubstr("expected a node type after DEF X, got 'USE'")));
  EXPECT_EQ(Lexer::describe(Token{TokenKind::kEnd}), "end of file");
  EXPECT_EQ(Lexer::describe(Token{TokenKind::kWord,
                                  std::string_view("abcdefghijklmnopqrstuvwxyzabcdefghijklmnopq")}),
            "'abcdefghijklmnopqrstuvwxyzabcdefghijklmn'...");
}

}  // namespace
}  // namespace lodforge::vrml1::detail
