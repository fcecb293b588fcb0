// The VRML 1.0 lexer. Tokens are views into the input; numbers are parsed in
// place with fast_float (floats) and a hand-written loop (integers), which is
// what lets the reader go several times faster than Coin's on big files.
#include "lodforge/io/vrml1/lexer.h"

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "lodforge/core/error.h"

namespace lodforge::vrml1::detail {

Lexer::Lexer(std::string_view text, std::string source_name)
    : text_(text),
      source_name_(std::move(source_name)),
      cursor_(text.data()),
      end_(text.data() + text.size()),
      line_start_(text.data()) {}

void Lexer::skip_space(bool commas) {
  const char* p = cursor_;
  while (p < end_) {
    char c = *p;
    if (ends_line(p, end_)) {
      ++line_;
      line_start_ = ++p;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v' ||
               (commas && c == ',')) {
      ++p;
    } else if (c == '#') {
      while (p < end_ && !ends_comment(*p)) ++p;
    } else {
      break;
    }
  }
  cursor_ = p;
}

Token Lexer::scan() {
  skip_space();
  Token t;
  t.line = line_;
  t.col = column();
  if (cursor_ >= end_) {
    t.kind = TokenKind::kEnd;
    return t;
  }
  const char* start = cursor_;
  char c = *cursor_;
  auto single = [&](TokenKind k) {
    t.kind = k;
    t.text = {cursor_, 1};
    ++cursor_;
    return t;
  };
  switch (c) {
    case '{':
      return single(TokenKind::kLBrace);
    case '}':
      return single(TokenKind::kRBrace);
    case '[':
      return single(TokenKind::kLBracket);
    case ']':
      return single(TokenKind::kRBracket);
    case '(':
      return single(TokenKind::kLParen);
    case ')':
      return single(TokenKind::kRParen);
    case ',':
      return single(TokenKind::kComma);
    case '|':
      return single(TokenKind::kBar);
    case '"': {
      const char* p = cursor_ + 1;
      while (p < end_ && *p != '"') {
        if (*p == '\\' && p + 1 < end_) ++p;
        if (ends_line(p, end_)) {
          ++line_;
          line_start_ = p + 1;
        }
        ++p;
      }
      if (p >= end_) {
        Token at = t;
        at.kind = TokenKind::kEnd;
        fail(at, "unterminated string (missing closing '\"')");
      }
      cursor_ = p + 1;
      t.kind = TokenKind::kString;
      t.text = {start, static_cast<std::size_t>(cursor_ - start)};
      return t;
    }
    default:
      break;
  }
  const char* p = cursor_;
  while (p < end_ && !is_delimiter(*p)) ++p;
  if (p == cursor_) {
    // A NUL or other byte that is a delimiter but no token: report it.
    t.kind = TokenKind::kWord;
    t.text = {cursor_, 1};
    fail(t, fmt::format("unexpected character (byte {:#04x})",
                        static_cast<unsigned>(static_cast<unsigned char>(c))));
  }
  cursor_ = p;
  t.kind = TokenKind::kWord;
  t.text = {start, static_cast<std::size_t>(p - start)};
  return t;
}

void Lexer::unpeek() {
  if (peeked_.kind == TokenKind::kEnd) {
    has_peeked_ = false;
    return;
  }
  cursor_ = peeked_.text.data();
  line_ = peeked_.line;
  line_start_ = cursor_ - (peeked_.col - 1);
  has_peeked_ = false;
}

const Token& Lexer::peek() {
  if (!has_peeked_) {
    peeked_ = scan();
    has_peeked_ = true;
  }
  return peeked_;
}

Token Lexer::next() {
  if (has_peeked_) {
    has_peeked_ = false;
    return peeked_;
  }
  return scan();
}

bool Lexer::accept_char(char c, bool commas) {
  if (has_peeked_) {
    if (peeked_.text.size() == 1 && peeked_.text[0] == c && peeked_.kind != TokenKind::kString &&
        peeked_.kind != TokenKind::kEnd) {
      has_peeked_ = false;
      return true;
    }
    if (!(commas && peeked_.kind == TokenKind::kComma)) return false;
    has_peeked_ = false;
  }
  skip_space(commas);
  if (cursor_ < end_ && *cursor_ == c) {
    ++cursor_;
    return true;
  }
  return false;
}

bool Lexer::read_float(float& out, bool commas) {
  if (has_peeked_) {
    // Rare: a value after a peeked token. Re-scan from the peeked word.
    if (peeked_.kind != TokenKind::kWord) return false;
    unpeek();
  }
  skip_space(commas);
  const char* p = cursor_;
  if (p < end_ && *p == '+') ++p;
  auto r = fast_float::from_chars(p, end_, out);
  if (r.ec != std::errc() || (r.ptr < end_ && !is_delimiter(*r.ptr))) {
    if (r.ec == std::errc::result_out_of_range) {
      cursor_ = r.ptr;
      return true;
    }
    return false;
  }
  cursor_ = r.ptr;
  return true;
}

bool Lexer::read_int(std::int32_t& out, bool commas) {
  if (has_peeked_) {
    if (peeked_.kind != TokenKind::kWord) return false;
    unpeek();
  }
  skip_space(commas);
  const char* p = cursor_;
  bool negative = false;
  if (p < end_ && (*p == '-' || *p == '+')) negative = *p++ == '-';
  std::uint64_t v = 0;
  const char* digits = p;
  if (end_ - p > 2 && p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
    p += 2;
    digits = p;
    while (p < end_) {
      char c = *p;
      unsigned d;
      if (c >= '0' && c <= '9')
        d = unsigned(c - '0');
      else if (c >= 'a' && c <= 'f')
        d = unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F')
        d = unsigned(c - 'A' + 10);
      else
        break;
      v = v * 16 + d;
      if (v > 0xFFFFFFFFull) return false;
      ++p;
    }
    if (p == digits || (p < end_ && !is_delimiter(*p))) return false;
    // Hex values are bit patterns (image pixels): keep all 32 bits.
    std::uint32_t bits = static_cast<std::uint32_t>(v);
    out = static_cast<std::int32_t>(negative ? 0u - bits : bits);
    cursor_ = p;
    return true;
  }
  while (p < end_ && *p >= '0' && *p <= '9') {
    v = v * 10 + unsigned(*p - '0');
    if (v > 0x80000000ull) return false;
    ++p;
  }
  if (p == digits || (p < end_ && !is_delimiter(*p))) return false;
  if (!negative && v > 0x7FFFFFFFull) return false;
  out = negative ? static_cast<std::int32_t>(-static_cast<std::int64_t>(v))
                 : static_cast<std::int32_t>(v);
  cursor_ = p;
  return true;
}

std::string_view Lexer::skip_balanced_body(const Token& open) {
  // Start right after the '{', so the body keeps its leading white space.
  has_peeked_ = false;
  cursor_ = open.text.data() + 1;
  line_ = open.line;
  line_start_ = open.text.data() - (open.col - 1);
  const char* begin = cursor_;
  int depth = 0;
  const char* p = cursor_;
  while (p < end_) {
    char c = *p;
    if (ends_line(p, end_)) {
      ++line_;
      line_start_ = p + 1;
    } else if (c == '#') {
      while (p < end_ && !ends_comment(*p)) ++p;
      continue;
    } else if (c == '"') {
      ++p;
      while (p < end_ && *p != '"') {
        if (*p == '\\' && p + 1 < end_) ++p;
        if (ends_line(p, end_)) {
          ++line_;
          line_start_ = p + 1;
        }
        ++p;
      }
    } else if (c == '{') {
      ++depth;
    } else if (c == '}') {
      if (depth == 0) {
        cursor_ = p;
        return {begin, static_cast<std::size_t>(p - begin)};
      }
      --depth;
    }
    ++p;
  }
  fail(open, "unterminated node: no '}' matches this '{'");
}

std::string Lexer::describe(const Token& t) {
  switch (t.kind) {
    case TokenKind::kEnd:
      return "end of file";
    case TokenKind::kString:
    case TokenKind::kWord: {
      std::string_view s = t.text.substr(0, 40);
      return fmt::format("'{}'{}", s, t.text.size() > 40 ? "..." : "");
    }
    default:
      return fmt::format("'{}'", t.text);
  }
}

void Lexer::expected(const Token& at, std::string_view what) const {
  fail(at, fmt::format("expected {}, got {}", what, describe(at)));
}

void Lexer::fail(const Token& at, const std::string& message) const {
  throw ParseError(source_name_, at.line, at.col, message);
}

void Lexer::fail_here(const std::string& message) {
  if (has_peeked_) {
    fail(peeked_, message);
  }
  skip_space();
  throw ParseError(source_name_, line_, column(), message);
}

std::string unquote(std::string_view quoted) {
  std::string s;
  if (quoted.size() < 2) return s;
  quoted = quoted.substr(1, quoted.size() - 2);
  s.reserve(quoted.size());
  for (std::size_t i = 0; i < quoted.size(); ++i) {
    if (quoted[i] == '\\' && i + 1 < quoted.size()) ++i;
    s += quoted[i];
  }
  return s;
}

HeaderLine header_line(const Lexer& lex) {
  std::string_view all = lex.rest();
  std::string_view first = all.substr(0, all.find_first_of("\r\n"));
  return {first, Token{TokenKind::kWord, first.substr(0, 40), 1, 1}};
}

Token read_node_name(Lexer& lex, std::string_view keyword) {
  Token name = lex.next();
  if (name.kind != TokenKind::kWord)
    lex.expected(name, fmt::format("a node name after {}", keyword));
  return name;
}

NodeStart read_node_start(Lexer& lex, const std::unordered_map<std::string, scene::NodePtr>& defs,
                          const Token& first) {
  NodeStart start;
  start.type = first;
  if (first.text == "USE") {
    const Token name = read_node_name(lex, "USE");
    start.used = use_of(lex, defs, name, name.text);
  } else if (first.text == "DEF") {
    start.def_name = std::string(read_node_name(lex, "DEF").text);
    start.type = lex.next();
    const Token& t = start.type;
    if (t.kind != TokenKind::kWord || t.text == "USE" || t.text == "DEF" || t.text == "NULL")
      lex.expected(t, "a node type after DEF " + start.def_name);
  }
  return start;
}

const scene::NodePtr& use_of(const Lexer& lex,
                             const std::unordered_map<std::string, scene::NodePtr>& defs,
                             const Token& name, std::string_view node_name) {
  auto it = defs.find(std::string(node_name));
  if (it == defs.end()) lex.fail(name, fmt::format("USE of undefined node name '{}'", node_name));
  return it->second;
}

scene::NodePtr open_node(Lexer& lex, const Token& type, Token& open) {
  auto node = std::make_shared<scene::Node>();
  node->type = std::string(type.text);
  node->first_line = type.line;
  open = lex.next();
  if (open.kind != TokenKind::kLBrace)
    lex.expected(open, fmt::format("'{{' after node type {}", type.text));
  return node;
}

void bad_value(Lexer& lex, const Token& field, scene::FieldType type, std::string_view what) {
  lex.fail_here(fmt::format("expected {} for {} field '{}', got {}", what, scene::type_name(type),
                            field.text, Lexer::describe(lex.peek())));
}

}  // namespace lodforge::vrml1::detail
