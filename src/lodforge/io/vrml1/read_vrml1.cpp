// VRML 1.0 reader: recursive descent over the grammar of the VRML 1.0
// specification (1995), the way Coin's SoBase::read / SoFieldData::read read
// it (header, DEF/USE, node, fields, values), without global registries.
//
// Decisions for real-world files:
//  | input                                  | what the reader does                          |
//  |----------------------------------------|-----------------------------------------------|
//  | unknown node with `fields [...]`        | parsed with the declared types, warning       |
//  | unknown node without declaration        | body kept verbatim, warning with line range   |
//  | unknown field of a known node           | value kept verbatim, warning                  |
//  | USE of a name never DEFined             | error                                         |
//  | DEF name reused                         | later USEs take the newest (as the spec says) |
//  | several top-level nodes                 | all kept (Coin's readAll does the same)       |
//  | nesting deeper than max_depth           | error (the parser's stack stays bounded)      |
//  | (inlined files nest below their inline)  |                                               |
//  | more than max_instances (max_triangles)  | error at the node that goes past the limit    |
//  | once expanded                            |                                               |
//  | inline: not a regular file, link loop    | error naming the file and line of the inline  |
//  | more than max_inline_files inlines read  | error                                         |
#include "lodforge/io/vrml1/read_vrml1.h"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/core/huge_pages.h"
#include "lodforge/io/vrml1/lexer.h"
#include "lodforge/scene/schema.h"

namespace lodforge::vrml1 {
namespace {

using detail::Lexer;
using detail::Token;
using detail::TokenKind;
using scene::FieldKind;
using scene::FieldType;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// What all the parsers of one scene (the file and its inlines) share.
struct SharedState {
  std::unordered_set<std::string> inline_stack;  ///< the files being read, outermost first
  std::uint64_t inline_files = 0;                ///< inlined files read so far
  /// What each node read expands to: instances are 1 + those of its
  /// children, triangles its own (a shape's) + those of its children.
  struct Expanded {
    std::uint64_t instances = 0, triangles = 0;
  };
  std::unordered_map<const Node*, Expanded> expanded;
};

std::uint64_t add_saturated(std::uint64_t a, std::uint64_t b) {
  return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

// The triangles (segments, points) a shape draws, estimated from its fields
// as read; primitives at the default tessellation of 24 segments.
std::uint64_t own_triangles(const Node& n) {
  constexpr std::uint64_t kSegments = 24;
  if (n.type == "IndexedFaceSet" || n.type == "IndexedLineSet") {
    const FieldValue* v = n.value("coordIndex");
    if (!v) return 0;
    std::uint64_t total = 0, run = 0;
    for (std::int32_t i : v->ints) {
      run = i < 0 ? 0 : run + 1;
      if (i >= 0 && run >= (n.type == "IndexedFaceSet" ? 3u : 2u)) ++total;
    }
    return total;
  }
  if (n.type == "PointSet") {
    const FieldValue* v = n.value("numPoints");
    return v && !v->ints.empty() && v->ints[0] > 0 ? std::uint64_t(v->ints[0]) : 1;
  }
  if (n.type == "Cube") return 12;
  if (n.type == "Sphere") return 2 * kSegments * kSegments;
  if (n.type == "Cylinder" || n.type == "Cone") return 4 * kSegments;
  if (n.type == "AsciiText") {
    const FieldValue* v = n.value("string");
    std::uint64_t chars = 0;
    if (v)
      for (const auto& s : v->strings) chars += s.size();
    return 2 * chars;
  }
  return 0;
}

bool is_number_start(std::string_view w) {
  if (w.empty()) return false;
  char c = w[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

class Parser {
 public:
  /// `depth`: the nesting depth of the file's top-level nodes (an inlined
  /// file's are one below their WWWInline).
  Parser(std::string_view text, const ReadOptions& options, ReadResult& result, SharedState& shared,
         int depth = 0)
      : lex_(text, options.source_name),
        options_(options),
        result_(result),
        shared_(shared),
        depth_(depth) {}

  void parse_file() {
    parse_header();
    SharedState::Expanded total;
    while (lex_.peek().kind != TokenKind::kEnd) {
      Token first = lex_.peek();
      result_.scene.roots.push_back(parse_node(depth_));
      const auto& e = shared_.expanded.at(result_.scene.roots.back().get());
      total.instances = add_saturated(total.instances, e.instances);
      total.triangles = add_saturated(total.triangles, e.triangles);
      check_expanded(first, total);
    }
  }

 private:
  void parse_header() {
    const auto [first, at] = detail::header_line(lex_);
    if (first.starts_with("#VRML V1.0 ascii") || first.starts_with("#Inventor V2.") ||
        first.starts_with("#Inventor V1.")) {
      if (first.starts_with("#Inventor") && first.find("binary") != std::string_view::npos)
        lex_.fail(at, "binary Open Inventor files are not supported; expected an ASCII file");
      result_.scene.header = std::string(first);
      inventor_ = scene::is_inventor_header(first);
      return;
    }
    if (first.starts_with("#VRML V2.0") || first.starts_with("#X3D"))
      lex_.fail(at, fmt::format("this is a {} file; lodforge reads VRML 1.0 "
                                "(expected header '#VRML V1.0 ascii')",
                                first.starts_with("#X3D") ? "X3D" : "VRML 2.0 (VRML97)"));
    lex_.fail(at, fmt::format("expected header '#VRML V1.0 ascii', got '{}'", first.substr(0, 40)));
  }

  NodePtr parse_node(int depth) { return parse_node_from(lex_.next(), depth); }

  // A node whose first token (type, DEF or USE) has been read already.
  NodePtr parse_node_from(const Token& t, int depth) {
    if (depth >= options_.max_depth)
      lex_.fail(t, fmt::format("nodes nested deeper than {} levels", options_.max_depth));
    if (t.kind != TokenKind::kWord) lex_.expected(t, "a node type, DEF or USE");
    detail::NodeStart start = detail::read_node_start(lex_, defs_, t);
    if (start.used) return start.used;
    const std::string& def_name = start.def_name;
    NodePtr node = parse_body(start.type, depth);
    if (!def_name.empty()) {
      node->name = def_name;
      // Bound after the body: a USE inside its own DEF cannot make a cycle.
      defs_[def_name] = node;
    }
    return node;
  }

  void check_expanded(const Token& at, const SharedState::Expanded& e) {
    if (options_.max_instances && e.instances > options_.max_instances)
      lex_.fail(at, fmt::format("the scene expands to more than {} node instances (each USE and "
                                "each inline repeats a subtree); refused (the limit of expanded "
                                "instances)",
                                options_.max_instances));
    if (options_.max_triangles && e.triangles > options_.max_triangles)
      lex_.fail(at, fmt::format("the scene's shapes, expanded, draw more than {} triangles (each "
                                "USE and each inline repeats a subtree); refused (the limit of "
                                "expanded triangles)",
                                options_.max_triangles));
  }

  // Records what a node whose children are complete expands to.
  NodePtr counted(NodePtr node, const Token& type) {
    SharedState::Expanded e{1, own_triangles(*node)};
    for (const auto& c : node->children) {
      const auto& ce = shared_.expanded.at(c.get());
      e.instances = add_saturated(e.instances, ce.instances);
      e.triangles = add_saturated(e.triangles, ce.triangles);
    }
    shared_.expanded[node.get()] = e;
    check_expanded(type, e);
    return node;
  }

  NodePtr parse_body(const Token& type, int depth) {
    Token open;
    NodePtr node = detail::open_node(lex_, type, open);
    // Inventor node types and fields count only in Inventor files.
    const scene::NodeSpec* spec = scene::find_node_spec(node->type, inventor_);

    const Token& first = lex_.peek();
    if (first.kind == TokenKind::kWord && first.text == "fields") {
      lex_.next();
      parse_declaration(*node);
    }
    const Token& second = lex_.peek();
    if (node->has_declaration && second.kind == TokenKind::kWord && second.text == "isA") {
      lex_.next();
      parse_is_a(*node);
    }
    if (!spec && !node->has_declaration) {
      node->is_raw = true;
      node->raw_body = std::string(lex_.skip_balanced_body(open));
      lex_.next();  // the closing brace
      node->last_line = lex_.line();
      result_.log.warn(
          LogCategory::kParse,
          fmt::format("{}:{}-{}: unknown node type >{}< kept as it is", options_.source_name,
                      node->first_line, node->last_line, node->type));
      return counted(node, type);
    }
    if (!spec) {
      result_.log.warn(LogCategory::kParse,
                       fmt::format("{}:{}: extension node type >{}< read from its field "
                                   "declaration",
                                   options_.source_name, node->first_line, node->type));
    }
    bool may_have_children = spec ? spec->group : true;
    while (true) {
      const Token& t = lex_.peek();
      if (t.kind == TokenKind::kRBrace) {
        lex_.next();
        break;
      }
      if (t.kind != TokenKind::kWord)
        lex_.expected(t, fmt::format("a field name, a child node or '}}' in {}", node->type));
      Token word = lex_.next();
      FieldType ftype;
      const std::vector<std::string>* enum_names = nullptr;
      if (find_field(*node, spec, word.text, ftype, enum_names)) {
        if (node->find(word.text))
          result_.log.warn(
              LogCategory::kParse,
              fmt::format("{}:{}:{}: field >{}< of {} given twice; the last value "
                          "counts",
                          options_.source_name, word.line, word.col, word.text, node->type));
        scene::Field f;
        f.name = std::string(word.text);
        if (!parse_value_marks(f, depth)) {
          f.value = ftype.kind == FieldKind::kNode ? parse_node_value(ftype, word, depth)
                                                   : parse_value(ftype, word, enum_names);
          parse_value_marks(f, depth);
        } else {
          f.no_value = true;
          if (const scene::FieldSpec* fs = spec ? spec->field(word.text, inventor_) : nullptr)
            f.value = fs->default_value;
          else
            f.value.type = ftype;
        }
        node->fields.push_back(std::move(f));
        continue;
      }
      if (word.text == "DEF" || word.text == "USE" || lex_.peek().kind == TokenKind::kLBrace) {
        if (!may_have_children)
          lex_.fail(word, fmt::format("{} cannot have children; expected a field of {} or '}}', "
                                      "got {}",
                                      node->type, node->type, Lexer::describe(word)));
        node->children.push_back(parse_node_from(word, depth + 1));
        continue;
      }
      // An unknown field of a known node: keep its text as it is. Its name must
      // look like a name (a number here is stray data, and would make the
      // extent of the verbatim values ambiguous when written back; `~` and
      // `=` are Inventor's marks after a value, and would join the field
      // before).
      if (is_number_start(word.text) || word.text == "~" || word.text == "=")
        lex_.expected(word, fmt::format("a field name, a child node or '}}' in {}", node->type));
      scene::Field f;
      f.name = std::string(word.text);
      f.is_raw = true;
      if (!parse_value_marks(f, depth)) {
        f.raw = std::string(parse_raw_value(word));
        parse_value_marks(f, depth);
      } else {
        f.no_value = true;
      }
      result_.log.warn(
          LogCategory::kParse,
          fmt::format("{}:{}:{}: unknown field >{}< of {} kept as it is", options_.source_name,
                      word.line, word.col, word.text, node->type));
      node->fields.push_back(std::move(f));
    }
    node->last_line = lex_.line();
    if (node->type == "WWWInline" && options_.read_inlines) read_inline(*node, depth);
    return counted(node, type);
  }

  // Open Inventor's marks after a field's value, or in its place: the ignore
  // flag '~' and a connection '= NODE . field' (NODE an engine or a node,
  // with DEF/USE; kept verbatim, its DEFs bound). Returns true if any was read.
  bool parse_value_marks(scene::Field& f, int depth) {
    bool any = false;
    while (lex_.peek().kind == TokenKind::kWord) {
      const Token t = lex_.peek();
      if (t.text == "~") {
        lex_.next();
        f.ignored = true;
        any = true;
      } else if (t.text == "=" && f.connection.empty()) {
        lex_.next();
        const Token from = lex_.next();
        Token dot;
        if (from.kind == TokenKind::kWord && from.text == "USE" &&
            lex_.peek().kind == TokenKind::kWord &&
            lex_.peek().text.find('.') != std::string_view::npos) {
          // "USE name.field": a name holds no '.', so the word splits there.
          const Token name = lex_.next();
          const std::string_view node_name = name.text.substr(0, name.text.find('.'));
          detail::use_of(lex_, defs_, name, node_name);
          dot = name;
          dot.text = name.text.substr(node_name.size());
        } else {
          parse_node_from(from, depth + 1);
          dot = lex_.next();
        }
        Token last = dot;
        if (dot.kind == TokenKind::kWord && dot.text == ".") {
          last = lex_.next();
          if (last.kind != TokenKind::kWord)
            lex_.expected(last, fmt::format("the name of the field connected to '{}'", f.name));
        } else if (dot.kind != TokenKind::kWord || dot.text.size() < 2 || dot.text[0] != '.') {
          lex_.expected(dot,
                        fmt::format("'.' and a field name after the connection of '{}'", f.name));
        }
        const char* end = last.text.data() + last.text.size();
        f.connection.assign(from.text.data(), static_cast<std::size_t>(end - from.text.data()));
        any = true;
      } else {
        break;
      }
    }
    return any;
  }

  // An SFNode / MFNode value: a node (DEF, USE or a body), NULL, or for
  // MFNode a bracketed list of them.
  FieldValue parse_node_value(FieldType type, const Token& field, int depth) {
    FieldValue v;
    v.type = type;
    auto one = [&](Token t) {
      if (t.kind == TokenKind::kWord && t.text == "NULL") return;
      if (t.kind != TokenKind::kWord || is_number_start(t.text))
        lex_.expected(t, fmt::format("a node or NULL for field '{}'", field.text));
      v.nodes.push_back(parse_node_from(t, depth + 1));
    };
    Token t = lex_.next();
    if (!type.multi || t.kind != TokenKind::kLBracket) {
      one(t);
      return v;
    }
    while (true) {
      Token n = lex_.next();
      if (n.kind == TokenKind::kComma) continue;
      if (n.kind == TokenKind::kRBracket) break;
      if (n.kind == TokenKind::kEnd)
        lex_.expected(n, fmt::format("a node or ']' for field '{}'", field.text));
      one(n);
    }
    return v;
  }

  bool find_field(const Node& node, const scene::NodeSpec* spec, std::string_view name,
                  FieldType& type, const std::vector<std::string>*& enum_names) {
    if (spec) {
      if (const scene::FieldSpec* fs = spec->field(name, inventor_)) {
        type = fs->type;
        enum_names = &fs->enum_names;
        return true;
      }
    }
    for (const auto& d : node.declared) {
      if (d.name == name) {
        type = d.type;
        return true;
      }
    }
    return false;
  }

  void parse_declaration(Node& node) {
    Token open = lex_.next();
    if (open.kind != TokenKind::kLBracket) lex_.expected(open, "'[' after 'fields'");
    node.has_declaration = true;
    while (true) {
      Token t = lex_.next();
      if (t.kind == TokenKind::kComma) continue;
      if (t.kind == TokenKind::kRBracket) break;
      scene::FieldDecl d;
      // SFNode / MFNode and SFUInt32 / MFUInt32 are Inventor's types.
      if (t.kind != TokenKind::kWord || !scene::parse_type_name(t.text, d.type) ||
          (!inventor_ && (d.type.kind == FieldKind::kNode || d.type.kind == FieldKind::kUInt32)))
        lex_.expected(t, "a field type such as SFFloat or MFVec3f, or ']'");
      Token name = lex_.next();
      if (name.kind != TokenKind::kWord) lex_.expected(name, "a field name");
      d.name = std::string(name.text);
      node.declared.push_back(std::move(d));
    }
  }

  void parse_is_a(Node& node) {
    Token t = lex_.peek();
    if (t.kind == TokenKind::kString) {
      node.is_a.push_back(detail::unquote(lex_.next().text));
      return;
    }
    Token open = lex_.next();
    if (open.kind != TokenKind::kLBracket) lex_.expected(open, "'[' or a string after 'isA'");
    while (true) {
      Token s = lex_.next();
      if (s.kind == TokenKind::kComma) continue;
      if (s.kind == TokenKind::kRBracket) break;
      if (s.kind == TokenKind::kString)
        node.is_a.push_back(detail::unquote(s.text));
      else if (s.kind == TokenKind::kWord)
        node.is_a.push_back(std::string(s.text));
      else
        lex_.expected(s, "a node type name or ']'");
    }
  }

  // The text of a value whose type is unknown: a bracketed list, a
  // parenthesised bit mask, or one token followed by any numbers.
  std::string_view parse_raw_value(const Token& field) {
    const Token& first = lex_.peek();
    if (first.kind == TokenKind::kEnd || first.kind == TokenKind::kRBrace)
      lex_.expected(first, fmt::format("a value for field '{}'", field.text));
    Token t = lex_.next();
    Token last = t;
    if (t.kind == TokenKind::kLBracket || t.kind == TokenKind::kLParen) {
      TokenKind close = t.kind == TokenKind::kLBracket ? TokenKind::kRBracket : TokenKind::kRParen;
      int depth = 1;
      while (depth > 0) {
        last = lex_.next();
        if (last.kind == TokenKind::kEnd)
          lex_.fail(t, fmt::format("unterminated value of field '{}'", field.text));
        if (last.kind == t.kind) ++depth;
        if (last.kind == close) --depth;
      }
    } else {
      while (lex_.peek().kind == TokenKind::kWord && is_number_start(lex_.peek().text))
        last = lex_.next();
    }
    // From the first token to the end of the last: comments after it stay out.
    const char* begin = t.text.data();
    const char* end = last.text.data() + last.text.size();
    return {begin, static_cast<std::size_t>(end - begin)};
  }

  [[noreturn]] void bad_value(const Token& field, FieldType type, std::string_view what) {
    detail::bad_value(lex_, field, type, what);
  }

  float read_float(const Token& field, FieldType type, bool commas) {
    float v;
    if (!lex_.read_float(v, commas)) bad_value(field, type, "a number");
    return v;
  }

  std::int32_t read_int(const Token& field, FieldType type, bool commas) {
    std::int32_t v;
    if (!lex_.read_int(v, commas)) bad_value(field, type, "an integer");
    return v;
  }

  // One value of the field's base kind, appended to `out`.
  void parse_one(FieldValue& out, const Token& field, bool in_list,
                 const std::vector<std::string>* enum_names) {
    FieldType type = out.type;
    switch (type.kind) {
      case FieldKind::kColor:
      case FieldKind::kFloat:
      case FieldKind::kMatrix:
      case FieldKind::kRotation:
      case FieldKind::kVec2f:
      case FieldKind::kVec3f: {
        int n = scene::float_components(type.kind);
        for (int i = 0; i < n; ++i)
          out.floats.push_back(read_float(field, type, in_list && i == 0));
        return;
      }
      case FieldKind::kLong:
      case FieldKind::kUInt32:
        out.ints.push_back(read_int(field, type, in_list));
        return;
      case FieldKind::kNode:
        lex_.fail_here(fmt::format("node field '{}' in a list", field.text));
      case FieldKind::kBool: {
        if (in_list) lex_.skip_space(true);
        Token t = lex_.next();
        if (t.text == "TRUE" || t.text == "1")
          out.ints.push_back(1);
        else if (t.text == "FALSE" || t.text == "0")
          out.ints.push_back(0);
        else
          lex_.fail(t, fmt::format("expected TRUE or FALSE for field '{}', got {}", field.text,
                                   Lexer::describe(t)));
        return;
      }
      case FieldKind::kString: {
        if (in_list) lex_.skip_space(true);
        Token t = lex_.next();
        if (t.kind == TokenKind::kString)
          out.strings.push_back(detail::unquote(t.text));
        else if (t.kind == TokenKind::kWord)
          out.strings.emplace_back(t.text);
        else
          lex_.expected(t, fmt::format("a string for field '{}'", field.text));
        return;
      }
      case FieldKind::kEnum: {
        if (in_list) lex_.skip_space(true);
        Token t = lex_.next();
        if (t.kind != TokenKind::kWord)
          lex_.expected(t, fmt::format("a name for field '{}'", field.text));
        check_enum(t, field, enum_names);
        out.strings.emplace_back(t.text);
        return;
      }
      case FieldKind::kBitMask: {
        Token t = lex_.next();
        if (t.kind == TokenKind::kWord) {
          check_enum(t, field, enum_names);
          out.strings.emplace_back(t.text);
          return;
        }
        if (t.kind != TokenKind::kLParen)
          lex_.expected(t, fmt::format("a flag name or '(' for field '{}'", field.text));
        while (true) {
          Token f = lex_.next();
          if (f.kind == TokenKind::kRParen) break;
          if (f.kind == TokenKind::kBar) continue;
          if (f.kind != TokenKind::kWord)
            lex_.expected(f, fmt::format("a flag name, '|' or ')' for field '{}'", field.text));
          check_enum(f, field, enum_names);
          out.strings.emplace_back(f.text);
        }
        return;
      }
      case FieldKind::kImage: {
        std::int32_t w = read_int(field, type, in_list);
        std::int32_t h = read_int(field, type, false);
        std::int32_t nc = read_int(field, type, false);
        if (w < 0 || h < 0 || nc < 0 || nc > 4 || std::int64_t(w) * h > (1 << 26))
          lex_.fail_here(
              fmt::format("bad image size {} x {} x {} in field '{}'", w, h, nc, field.text));
        out.ints.insert(out.ints.end(), {w, h, nc});
        for (std::int64_t i = 0, n = std::int64_t(w) * h; i < n; ++i)
          out.ints.push_back(read_int(field, type, false));
        return;
      }
    }
  }

  void check_enum(const Token& t, const Token& field, const std::vector<std::string>* names) {
    if (!names || names->empty()) return;
    for (const auto& n : *names)
      if (n == t.text) return;
    std::string all;
    for (const auto& n : *names) all += (all.empty() ? "" : ", ") + n;
    lex_.fail(t, fmt::format("expected one of {} for field '{}', got {}", all, field.text,
                             Lexer::describe(t)));
  }

  // A long array grows in one allocation instead of about log2(n) copies:
  // after its first kSampleValues values, the values are reserved that the
  // text up to the next ']' holds at the bytes per value seen so far (a
  // guess; a wrong one costs only growth as usual), on huge pages.
  static constexpr std::size_t kSampleValues = 4096;
  template <class T>
  void reserve_for_rest(std::vector<T>& values, const char* start) {
    const std::string_view rest = lex_.rest();
    const std::size_t close = rest.find(']');
    if (close == std::string_view::npos) return;
    const double per_value = double(lex_.cursor() - start) / double(values.size());
    values.reserve(values.size() + std::size_t(double(close) / per_value * 1.02) + 16);
    advise_huge_pages(values);
  }

  FieldValue parse_value(FieldType type, const Token& field,
                         const std::vector<std::string>* enum_names) {
    FieldValue v;
    v.type = type;
    if (!type.multi) {
      parse_one(v, field, false, enum_names);
      return v;
    }
    if (!lex_.accept_char('[')) {
      parse_one(v, field, false, enum_names);
      return v;
    }
    // The hot loops of big files: numbers straight into the vectors.
    if (scene::float_components(type.kind) > 0) {
      int n = scene::float_components(type.kind);
      float f;
      std::size_t count = 0;
      const char* start = lex_.cursor();
      while (lex_.read_float(f, true)) {
        v.floats.push_back(f);
        if (++count == kSampleValues) reserve_for_rest(v.floats, start);
      }
      if (!lex_.accept_char(']', true)) bad_value(field, type, "a number or ']'");
      if (count % static_cast<std::size_t>(n) != 0)
        lex_.fail(field, fmt::format("{} field '{}' needs a multiple of {} numbers, got {}",
                                     scene::type_name(type), field.text, n, count));
      return v;
    }
    if (type.kind == FieldKind::kLong || type.kind == FieldKind::kUInt32) {
      std::int32_t i;
      const char* start = lex_.cursor();
      while (lex_.read_int(i, true)) {
        v.ints.push_back(i);
        if (v.ints.size() == kSampleValues) reserve_for_rest(v.ints, start);
      }
      if (!lex_.accept_char(']', true)) bad_value(field, type, "an integer or ']'");
      return v;
    }
    while (!lex_.accept_char(']', true)) {
      if (lex_.peek().kind == TokenKind::kEnd) bad_value(field, type, "a value or ']'");
      parse_one(v, field, true, enum_names);
    }
    return v;
  }

  void read_inline(Node& node, int depth) {
    const FieldValue* name = node.value("name");
    if (!name || name->strings.empty() || name->strings[0].empty()) return;
    const std::string& url = name->strings[0];
    auto warn = [&](const std::string& why) {
      result_.log.warn(LogCategory::kParse,
                       fmt::format("{}:{}: WWWInline '{}' not read: {}", options_.source_name,
                                   node.first_line, url, why));
    };
    if (url.find("://") != std::string::npos && !url.starts_with("file://")) {
      warn("lodforge never reads over a network");
      return;
    }
    namespace fs = std::filesystem;
    auto refuse = [&](const std::string& why) {
      throw DataError(fmt::format("{}:{}: WWWInline '{}' {}; refused", options_.source_name,
                                  node.first_line, url, why));
    };
    std::string rel = url.starts_with("file://") ? url.substr(7) : url;
    fs::path base, target;
    try {
      base = fs::weakly_canonical(fs::path(options_.base_dir));
      target = fs::weakly_canonical(base / rel);
    } catch (const fs::filesystem_error& e) {
      refuse(fmt::format("cannot be resolved: {}", e.code().message()));
    }
    auto [b, t] = std::mismatch(base.begin(), base.end(), target.begin(), target.end());
    if (b != base.end()) refuse(fmt::format("leaves the scene's folder {}", base.string()));
    std::error_code ec;
    const fs::file_status status = fs::status(target, ec);
    if (!fs::exists(status)) {
      warn("file not found");
      return;
    }
    // A FIFO or a device would block or never end: only regular files are read.
    if (!fs::is_regular_file(status)) refuse("is not a regular file");
    if (shared_.inline_stack.count(target.string())) {
      warn("it includes itself (inline cycle)");
      return;
    }
    if (options_.max_inline_files && ++shared_.inline_files > options_.max_inline_files)
      refuse(fmt::format("goes past the limit of {} inlined files", options_.max_inline_files));
    shared_.inline_stack.insert(target.string());
    ReadOptions sub = options_;
    sub.source_name = target.string();
    sub.base_dir = target.parent_path().string();
    ReadResult r;
    std::string text = read_file(target.string());
    Parser p(text, sub, r, shared_, depth + 1);
    p.parse_file();
    shared_.inline_stack.erase(target.string());
    result_.log.merge(r.log);
    for (auto& root : r.scene.roots) node.children.push_back(std::move(root));
  }

  Lexer lex_;
  const ReadOptions& options_;
  ReadResult& result_;
  SharedState& shared_;
  const int depth_;
  std::unordered_map<std::string, NodePtr> defs_;
  bool inventor_ = false;  // an Inventor header: Inventor node types and fields are known
};

}  // namespace

ReadResult read_vrml1(std::string_view text, const ReadOptions& options) {
  ReadResult result;
  SharedState shared;
  Parser parser(text, options, result, shared);
  parser.parse_file();
  return result;
}

ReadResult read_vrml1_file(const std::string& path, ReadOptions options) {
  options.source_name = path == "-" ? "<stdin>" : path;
  if (path != "-") {
    std::filesystem::path p(path);
    options.base_dir = p.has_parent_path() ? p.parent_path().string() : ".";
  }
  const FileBytes text(path);
  return read_vrml1(text.view(), options);
}

}  // namespace lodforge::vrml1
