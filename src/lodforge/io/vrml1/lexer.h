#pragma once
/// Internal: the VRML 1.0 lexer used by the parser. It works on the whole text
/// in memory and hands out views into it: no allocation per token. Positions
/// are tracked as it goes (line, and the start of the line for columns).
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "lodforge/scene/node.h"

namespace lodforge::vrml1::detail {

enum class TokenKind : std::uint8_t {
  kEnd,
  kWord,    ///< identifiers and numbers: anything up to a delimiter
  kString,  ///< "quoted" (text holds the quoted source, escapes not resolved)
  kLBrace,
  kRBrace,
  kLBracket,
  kRBracket,
  kLParen,
  kRParen,
  kComma,
  kBar,
};

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string_view text;
  int line = 0;
  int col = 0;
};

class Lexer {
 public:
  Lexer(std::string_view text, std::string source_name);

  /// The next token without consuming it.
  const Token& peek();
  /// Consumes and returns the next token.
  Token next();
  /// Skips white space and comments (and commas when `commas`).
  void skip_space(bool commas = false);

  /// Fast paths for values: skip space (and commas), then read a number at the
  /// cursor. Return false if no number starts there (nothing is consumed).
  bool read_float(float& out, bool commas);
  bool read_int(std::int32_t& out, bool commas);
  /// True if the next character (after space) is `c`; consumes it if so.
  bool accept_char(char c, bool commas = false);

  /// The raw text from `begin` (a pointer into the input) to the cursor.
  std::string_view slice_from(const char* begin) const {
    return {begin, static_cast<std::size_t>(cursor_ - begin)};
  }
  const char* cursor() { return cursor_; }
  /// The unread text.
  std::string_view rest() const { return {cursor_, static_cast<std::size_t>(end_ - cursor_)}; }
  /// Skips the body of the node opened by `open` (a '{' token already read):
  /// everything up to (not including) the matching '}', honouring strings and
  /// comments. Returns the body text. Throws on end of input.
  std::string_view skip_balanced_body(const Token& open);

  int line() const { return line_; }
  int column() const { return static_cast<int>(cursor_ - line_start_) + 1; }
  const std::string& source_name() const { return source_name_; }

  /// Throws ParseError at `at` with "expected `expected`, got <token>".
  [[noreturn]] void expected(const Token& at, std::string_view expected) const;
  /// Throws ParseError at `at` with `message`.
  [[noreturn]] void fail(const Token& at, const std::string& message) const;
  /// Throws ParseError at the cursor.
  [[noreturn]] void fail_here(const std::string& message);

  /// A short printable description of a token for messages.
  static std::string describe(const Token& t);

 private:
  Token scan();
  /// Puts a peeked token back, so that the cursor is at its start again.
  void unpeek();
  std::string_view text_;
  std::string source_name_;
  const char* cursor_;
  const char* end_;
  const char* line_start_;
  int line_ = 1;
  Token peeked_;
  bool has_peeked_ = false;
};

/// True if the character at `p` (before `end`) ends a line: a linefeed, or a
/// carriage return not followed by one (old Mac files end lines with it alone).
inline bool ends_line(const char* p, const char* end) {
  return *p == '\n' || (*p == '\r' && (p + 1 == end || p[1] != '\n'));
}

/// True if `c` ends a comment: a line terminator, linefeed or carriage return.
inline bool ends_comment(char c) {
  return c == '\n' || c == '\r';
}

/// True if `c` ends a word.
inline bool is_delimiter(char c) {
  switch (c) {
    case ' ':
    case '\t':
    case '\r':
    case '\n':
    case '\f':
    case '\v':
    case '{':
    case '}':
    case '[':
    case ']':
    case '(':
    case ')':
    case ',':
    case '|':
    case '"':
    case '#':
    case '\0':
      return true;
    default:
      return false;
  }
}

/// The header: the unread text's first line (up to a linefeed or carriage
/// return), and a
/// token for messages at its start (its first 40 characters).
struct HeaderLine {
  std::string_view text;
  Token at;
};
HeaderLine header_line(const Lexer& lex);

/// The name after DEF or USE (`keyword`): the next token, which must be a
/// word (else ParseError "expected a node name after KEYWORD").
Token read_node_name(Lexer& lex, std::string_view keyword);

/// The start of a node whose first token `first` (a word) has been read:
/// `USE NAME` gives the node NAME is bound to in `defs` as `used`; `DEF NAME
/// TYPE` gives NAME as `def_name` and the TYPE token (a word other than DEF,
/// USE and NULL, else ParseError) as `type`; anything else is the type.
struct NodeStart {
  scene::NodePtr used;
  std::string def_name;
  Token type;
};
NodeStart read_node_start(Lexer& lex, const std::unordered_map<std::string, scene::NodePtr>& defs,
                          const Token& first);

/// The node a USE names (`name`, read by read_node_name) is bound to in
/// `defs`; ParseError "USE of undefined node name 'NAME'" if none.
const scene::NodePtr& use_of(const Lexer& lex,
                             const std::unordered_map<std::string, scene::NodePtr>& defs,
                             const Token& name, std::string_view node_name);

/// A node of type `type` (its token read) whose opening '{' is read next
/// (else ParseError "expected '{' after node type TYPE"); `open` gets the '{'.
scene::NodePtr open_node(Lexer& lex, const Token& type, Token& open);

/// ParseError at the lexer's cursor: "expected WHAT for TYPE field 'FIELD',
/// got <the next token>".
[[noreturn]] void bad_value(Lexer& lex, const Token& field, scene::FieldType type,
                            std::string_view what);

/// Resolves the escapes of a quoted string token ("a \"b\"" -> a "b").
std::string unquote(std::string_view quoted);

}  // namespace lodforge::vrml1::detail
