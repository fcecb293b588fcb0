// VRML97 / X3D classic reader: recursive descent over the grammar of
// ISO/IEC 14772-1 annex A (and ISO/IEC 19776-2 for X3D's header statements),
// on the VRML 1.0 lexer (the token syntax is the same).
//
// Decisions for real-world files:
//  | input                                   | what the reader does                       |
//  |-----------------------------------------|--------------------------------------------|
//  | field of a node in the table below      | typed; a wrong value is an error           |
//  | any other field                         | node(s) if it lexically is one, else raw   |
//  | PROTO / EXTERNPROTO / ROUTE / X3D        | kept verbatim (a PROTO body is not parsed:  |
//  | header statements                        | its DEFs and IS are local to it)           |
//  | instance of a PROTO or unknown node type | parsed by the lexical rule above           |
//  | USE of a name never DEFined              | error                                      |
//  | DEF name reused                          | later USEs take the newest                 |
#include "lodforge/io/vrml97/read_vrml97.h"

#include <fmt/format.h>

#include <filesystem>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/lexer.h"

namespace lodforge::vrml97 {
namespace {

using scene::FieldKind;
using scene::FieldType;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;
using vrml1::detail::Lexer;
using vrml1::detail::Token;
namespace detail = vrml1::detail;
using vrml1::detail::TokenKind;

// The typed fields of the node types the LOD pipeline interprets, as
// "TYPE name" pairs. SFColorRGBA values are held as 4-float (Rotation-sized)
// values. Fields not listed are typed by their lexical form.
struct TypedNode {
  std::string_view type;
  std::string_view fields;
};
constexpr std::string_view kGeometryNodes =
    "SFNode coord SFNode normal SFNode color SFNode texCoord SFBool ccw SFBool solid "
    "SFBool colorPerVertex SFBool normalPerVertex ";
constexpr TypedNode kTypedNodes[] = {
    {"Transform",
     "SFVec3f translation SFRotation rotation SFVec3f scale SFRotation scaleOrientation "
     "SFVec3f center MFNode children SFVec3f bboxCenter SFVec3f bboxSize"},
    {"Group", "MFNode children SFVec3f bboxCenter SFVec3f bboxSize"},
    {"Shape", "SFNode appearance SFNode geometry"},
    {"Appearance", "SFNode material SFNode texture SFNode textureTransform"},
    {"Material",
     "SFColor diffuseColor SFFloat ambientIntensity SFColor specularColor SFColor emissiveColor "
     "SFFloat shininess SFFloat transparency"},
    {"IndexedFaceSet",
     "MFInt32 coordIndex MFInt32 normalIndex MFInt32 colorIndex MFInt32 texCoordIndex "
     "SFBool convex SFFloat creaseAngle "},
    {"IndexedLineSet",
     "MFInt32 coordIndex MFInt32 colorIndex SFBool colorPerVertex SFNode coord SFNode color"},
    {"IndexedTriangleSet", "MFInt32 index "},
    {"IndexedQuadSet", "MFInt32 index "},
    {"TriangleSet", ""},
    {"ElevationGrid",
     "SFInt32 xDimension SFInt32 zDimension SFFloat xSpacing SFFloat zSpacing MFFloat height "
     "SFFloat creaseAngle "},
    {"TextureTransform", "SFVec2f center SFFloat rotation SFVec2f scale SFVec2f translation"},
    {"Coordinate", "MFVec3f point"},
    {"Normal", "MFVec3f vector"},
    {"TextureCoordinate", "MFVec2f point"},
    {"Color", "MFColor color"},
    {"ColorRGBA", "MFColorRGBA color"},
    {"Box", "SFVec3f size SFBool solid"},
    {"Sphere", "SFFloat radius SFBool solid"},
    {"Cone", "SFFloat bottomRadius SFFloat height SFBool side SFBool bottom SFBool solid"},
    {"Cylinder", "SFFloat radius SFFloat height SFBool side SFBool top SFBool bottom SFBool solid"},
    {"LOD", "MFNode level MFNode children SFVec3f center MFFloat range"},
    {"Switch", "MFNode choice MFNode children SFInt32 whichChoice"},
    {"Viewpoint",
     "SFFloat fieldOfView SFVec3f position SFRotation orientation SFString description "
     "SFBool jump"},
    // File references (scene::relocate_references moves them with the scene).
    {"ImageTexture", "MFString url"},
    {"MovieTexture", "MFString url"},
    {"ImageCubeMapTexture", "MFString url"},
    {"ImageTexture3D", "MFString url"},
    {"AudioClip", "MFString url"},
    {"Inline", "MFString url"},
    {"Anchor", "MFString url"},
    {"Script", "MFString url"},
    {"ShaderPart", "MFString url"},
    {"ShaderProgram", "MFString url"},
    {"PackagedShader", "MFString url"},
    {"Background",
     "MFString backUrl MFString frontUrl MFString leftUrl MFString rightUrl MFString topUrl "
     "MFString bottomUrl"},
};

bool geometry_node(std::string_view type) {
  return type == "IndexedFaceSet" || type == "IndexedTriangleSet" || type == "IndexedQuadSet" ||
         type == "TriangleSet" || type == "ElevationGrid";
}

// VRML97 / X3D type names onto the scene's field kinds; false for types kept raw.
bool field_type_of(std::string_view name, FieldType& out) {
  if (name.size() < 3 || (name[0] != 'S' && name[0] != 'M') || name[1] != 'F') return false;
  const bool multi = name[0] == 'M';
  const std::string_view base = name.substr(2);
  static constexpr std::pair<std::string_view, FieldKind> kKinds[] = {
      {"Bool", FieldKind::kBool},          {"Color", FieldKind::kColor},
      {"ColorRGBA", FieldKind::kRotation}, {"Float", FieldKind::kFloat},
      {"Int32", FieldKind::kLong},         {"Node", FieldKind::kNode},
      {"Rotation", FieldKind::kRotation},  {"String", FieldKind::kString},
      {"Vec2f", FieldKind::kVec2f},        {"Vec3f", FieldKind::kVec3f},
  };
  for (const auto& [n, k] : kKinds)
    if (n == base) {
      out = {k, multi};
      return true;
    }
  return false;
}

}  // namespace

bool typed_field(std::string_view type, std::string_view field, FieldType& out) {
  for (const auto& t : kTypedNodes) {
    if (t.type != type) continue;
    std::string fields(t.fields);
    if (geometry_node(type)) fields += kGeometryNodes;
    std::size_t pos = 0;
    while (pos < fields.size()) {
      std::size_t sp = fields.find(' ', pos);
      std::size_t end = fields.find(' ', sp + 1);
      if (end == std::string::npos) end = fields.size();
      if (std::string_view(fields).substr(sp + 1, end - sp - 1) == field)
        return field_type_of(std::string_view(fields).substr(pos, sp - pos), out);
      pos = end + 1;
    }
    return false;
  }
  return false;
}

namespace {

bool is_number_start(std::string_view w) {
  if (w.empty()) return false;
  char c = w[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

bool is_statement_keyword(std::string_view w) {
  return w == "PROTO" || w == "EXTERNPROTO" || w == "ROUTE" || w == "PROFILE" || w == "COMPONENT" ||
         w == "META" || w == "UNIT" || w == "IMPORT" || w == "EXPORT";
}

bool is_access_keyword(std::string_view w) {
  return w == "field" || w == "exposedField" || w == "eventIn" || w == "eventOut" ||
         w == "initializeOnly" || w == "inputOutput" || w == "inputOnly" || w == "outputOnly";
}

class Parser {
 public:
  Parser(std::string_view text, const ReadOptions& options, ReadResult& result)
      : lex_(text, options.source_name), options_(options), result_(result) {}

  void parse_file() {
    parse_header();
    while (lex_.peek().kind != TokenKind::kEnd) {
      Token t = lex_.next();
      if (t.kind == TokenKind::kComma) continue;  // commas are white space in VRML97
      if (t.kind == TokenKind::kWord && is_statement_keyword(t.text)) {
        auto n = std::make_shared<Node>();
        n->type = std::string(t.text);
        n->statement = true;
        n->first_line = t.line;
        n->raw_body = std::string(parse_statement(t));
        n->last_line = lex_.line();
        result_.scene.roots.push_back(std::move(n));
        continue;
      }
      NodePtr n = parse_node_from(t, 0, "a node or a statement");
      if (!n) lex_.expected(t, "a node or a statement");
      result_.scene.roots.push_back(std::move(n));
    }
  }

 private:
  void parse_header() {
    const auto [first, at] = detail::header_line(lex_);
    if (!is_vrml97_header(first))
      lex_.fail(at, fmt::format("expected header '#VRML V2.0 utf8' or '#X3D V3.x utf8', got '{}'",
                                first.substr(0, 40)));
    result_.scene.header = std::string(first);
  }

  // The text of a statement after its keyword (already read), verbatim.
  std::string_view parse_statement(const Token& keyword) {
    const char* begin = lex_.peek().text.data();
    Token last = keyword;
    auto word = [&](std::string_view what) {
      last = lex_.next();
      if (last.kind != TokenKind::kWord && last.kind != TokenKind::kString)
        lex_.expected(last, fmt::format("{} in {}", what, keyword.text));
    };
    auto balanced = [&](TokenKind open, TokenKind close, std::string_view what) {
      Token o = lex_.next();
      if (o.kind != open) lex_.expected(o, fmt::format("{} in {}", what, keyword.text));
      last = skip_balanced(o, open, close);
    };
    const std::string_view k = keyword.text;
    if (k == "PROTO" || k == "EXTERNPROTO") {
      word("a name");
      balanced(TokenKind::kLBracket, TokenKind::kRBracket, "'[' (the interface)");
      if (k == "PROTO") {
        balanced(TokenKind::kLBrace, TokenKind::kRBrace, "'{' (the body)");
      } else if (lex_.peek().kind == TokenKind::kLBracket) {
        balanced(TokenKind::kLBracket, TokenKind::kRBracket, "'[' (the URLs)");
      } else {
        word("a URL");
      }
    } else if (k == "ROUTE") {
      word("a source node.field");
      word("TO");
      if (last.text != "TO") lex_.expected(last, "TO in ROUTE");
      word("a destination node.field");
    } else if (k == "PROFILE") {
      word("a profile name");
    } else if (k == "COMPONENT") {
      word("a component name");
      // "name:level" or "name : level"
      while (lex_.peek().kind == TokenKind::kWord &&
             (last.text.ends_with(':') || lex_.peek().text.starts_with(':')))
        word("a component level");
    } else if (k == "META") {
      word("a key");
      word("a value");
    } else if (k == "UNIT") {
      word("a category");
      word("a name");
      word("a conversion factor");
    } else {  // IMPORT, EXPORT
      word("a name");
      if (lex_.peek().kind == TokenKind::kWord && lex_.peek().text == "AS") {
        word("AS");
        word("a name");
      }
    }
    const char* end = last.text.data() + last.text.size();
    return {begin, static_cast<std::size_t>(end - begin)};
  }

  // Skips to the token closing `open` (read already); returns it.
  Token skip_balanced(const Token& open, TokenKind open_kind, TokenKind close_kind) {
    int depth = 1;
    Token t = open;
    while (depth > 0) {
      t = lex_.next();
      if (t.kind == TokenKind::kEnd) lex_.fail(open, "unterminated '[', '{' or '('");
      if (t.kind == open_kind) ++depth;
      if (t.kind == close_kind) --depth;
    }
    return t;
  }

  // A node (or NULL, returned as nullptr) whose first token has been read.
  NodePtr parse_node_from(const Token& t, int depth, std::string_view what) {
    if (depth >= options_.max_depth)
      lex_.fail(t, fmt::format("nodes nested deeper than {} levels", options_.max_depth));
    if (t.kind != TokenKind::kWord || is_number_start(t.text)) lex_.expected(t, what);
    if (t.text == "NULL") return nullptr;
    detail::NodeStart start = detail::read_node_start(lex_, defs_, t);
    if (start.used) return start.used;
    const std::string& def_name = start.def_name;
    if (is_number_start(start.type.text))
      lex_.expected(start.type, "a node type after DEF " + def_name);
    NodePtr node = parse_body(start.type, depth);
    if (!def_name.empty()) {
      node->name = def_name;
      defs_[def_name] = node;
    }
    return node;
  }

  NodePtr parse_body(const Token& type, int depth) {
    Token open;
    NodePtr node = detail::open_node(lex_, type, open);
    while (true) {
      Token word = lex_.next();
      if (word.kind == TokenKind::kComma) continue;  // commas are white space in VRML97
      if (word.kind == TokenKind::kRBrace) break;
      if (word.kind != TokenKind::kWord || is_number_start(word.text))
        lex_.expected(word, fmt::format("a field name or '}}' in {}", node->type));
      scene::Field f;
      f.name = std::string(word.text);
      if (is_statement_keyword(word.text)) {
        f.is_raw = true;
        f.raw = std::string(parse_statement(word));
      } else if (is_access_keyword(word.text) && lex_.peek().kind == TokenKind::kWord &&
                 (lex_.peek().text.starts_with("SF") || lex_.peek().text.starts_with("MF"))) {
        parse_declaration(f, word, depth);
      } else if (lex_.peek().kind == TokenKind::kWord && lex_.peek().text == "IS") {
        parse_is(f, word);
      } else {
        FieldType ftype;
        if (typed_field(node->type, word.text, ftype))
          f.value = ftype.kind == FieldKind::kNode ? parse_node_value(ftype, word, depth)
                                                   : parse_value(ftype, word);
        else
          parse_untyped(f, word, depth);
      }
      node->fields.push_back(std::move(f));
    }
    node->last_line = lex_.line();
    return node;
  }

  // `field IS name` (the field's name read, IS next): a raw field "IS name"
  // in a PROTO body, an error elsewhere.
  void parse_is(scene::Field& f, const Token& field) {
    if (!options_.proto_body)
      lex_.fail(field, fmt::format("IS outside a PROTO body (field '{}')", field.text));
    lex_.next();
    Token name = lex_.next();
    if (name.kind != TokenKind::kWord) lex_.expected(name, "an interface field name after IS");
    f.is_raw = true;
    f.raw = fmt::format("IS {}", name.text);
  }

  // `access TYPE name [value]`: the name of the field holds all three words.
  void parse_declaration(scene::Field& f, const Token& access, int depth) {
    Token type = lex_.next();
    Token name = lex_.next();
    if (name.kind != TokenKind::kWord) lex_.expected(name, "a field name after " + f.name);
    f.name = fmt::format("{} {} {}", access.text, type.text, name.text);
    const bool has_value = access.text == "field" || access.text == "exposedField" ||
                           access.text == "initializeOnly" || access.text == "inputOutput";
    if (lex_.peek().kind == TokenKind::kWord && lex_.peek().text == "IS") {
      parse_is(f, name);
      return;
    }
    FieldType ftype;
    if (has_value && field_type_of(type.text, ftype) && ftype.kind == FieldKind::kNode) {
      f.value = parse_node_value(ftype, name, depth);
      return;
    }
    f.is_raw = true;
    if (has_value)
      f.raw = std::string(parse_raw_value(name));
    else
      f.no_value = true;
  }

  // A field with no typed entry: node(s) if the value lexically is one,
  // else its text.
  void parse_untyped(scene::Field& f, const Token& field, int depth) {
    const Token& first = lex_.peek();
    if (first.kind == TokenKind::kWord && !is_number_start(first.text) && first.text != "TRUE" &&
        first.text != "FALSE") {
      // A word value that is not a number or a boolean: a node, DEF, USE or NULL.
      f.value = parse_node_value({FieldKind::kNode, false}, field, depth);
      return;
    }
    if (first.kind != TokenKind::kLBracket) {
      f.is_raw = true;
      f.raw = std::string(parse_raw_value(field));
      return;
    }
    Token open = lex_.next();
    const Token& second = lex_.peek();
    if (second.kind == TokenKind::kWord && !is_number_start(second.text) && second.text != "TRUE" &&
        second.text != "FALSE") {
      f.value = parse_node_list(field, depth);
      return;
    }
    Token last = skip_balanced(open, TokenKind::kLBracket, TokenKind::kRBracket);
    f.is_raw = true;
    const char* begin = open.text.data();
    f.raw.assign(begin, static_cast<std::size_t>(last.text.data() + last.text.size() - begin));
  }

  // An SFNode / MFNode value: a node, NULL, or for MFNode a bracketed list.
  FieldValue parse_node_value(FieldType type, const Token& field, int depth) {
    Token t = lex_.next();
    if (type.multi && t.kind == TokenKind::kLBracket) return parse_node_list(field, depth);
    FieldValue v;
    v.type = type;
    if (NodePtr n =
            parse_node_from(t, depth + 1, fmt::format("a node or NULL for field '{}'", field.text)))
      v.nodes.push_back(std::move(n));
    else if (type.multi)
      lex_.expected(t, fmt::format("a node for field '{}'", field.text));
    return v;
  }

  // The nodes of a list whose '[' has been read.
  FieldValue parse_node_list(const Token& field, int depth) {
    FieldValue v;
    v.type = {FieldKind::kNode, true};
    while (true) {
      Token n = lex_.next();
      if (n.kind == TokenKind::kComma) continue;
      if (n.kind == TokenKind::kRBracket) break;
      NodePtr node =
          parse_node_from(n, depth + 1, fmt::format("a node or ']' for field '{}'", field.text));
      if (!node) lex_.expected(n, fmt::format("a node or ']' for field '{}'", field.text));
      v.nodes.push_back(std::move(node));
    }
    return v;
  }

  // The text of an untyped value: a bracketed list, or one token followed
  // by any numbers.
  std::string_view parse_raw_value(const Token& field) {
    const Token& first = lex_.peek();
    if (first.kind == TokenKind::kEnd || first.kind == TokenKind::kRBrace ||
        first.kind == TokenKind::kRBracket)
      lex_.expected(first, fmt::format("a value for field '{}'", field.text));
    Token t = lex_.next();
    Token last = t;
    if (t.kind == TokenKind::kLBracket)
      last = skip_balanced(t, TokenKind::kLBracket, TokenKind::kRBracket);
    else
      while (lex_.peek().kind == TokenKind::kWord && is_number_start(lex_.peek().text))
        last = lex_.next();
    const char* begin = t.text.data();
    return {begin, static_cast<std::size_t>(last.text.data() + last.text.size() - begin)};
  }

  [[noreturn]] void bad_value(const Token& field, FieldType type, std::string_view what) {
    detail::bad_value(lex_, field, type, what);
  }

  void parse_one(FieldValue& out, const Token& field) {
    const FieldType type = out.type;
    if (const int n = scene::float_components(type.kind)) {
      float f;
      for (int i = 0; i < n; ++i) {
        if (!lex_.read_float(f, true)) bad_value(field, type, "a number");
        out.floats.push_back(f);
      }
      return;
    }
    if (type.kind == FieldKind::kLong) {
      std::int32_t i;
      if (!lex_.read_int(i, true)) bad_value(field, type, "an integer");
      out.ints.push_back(i);
      return;
    }
    lex_.skip_space(true);
    Token t = lex_.next();
    if (type.kind == FieldKind::kBool) {
      if (t.text != "TRUE" && t.text != "FALSE")
        lex_.fail(t, fmt::format("expected TRUE or FALSE for field '{}', got {}", field.text,
                                 Lexer::describe(t)));
      out.ints.push_back(t.text == "TRUE" ? 1 : 0);
      return;
    }
    if (t.kind != TokenKind::kString)
      lex_.expected(t, fmt::format("a string for field '{}'", field.text));
    out.strings.push_back(vrml1::detail::unquote(t.text));
  }

  FieldValue parse_value(FieldType type, const Token& field) {
    FieldValue v;
    v.type = type;
    if (!type.multi || !lex_.accept_char('[', true)) {
      parse_one(v, field);
      return v;
    }
    while (!lex_.accept_char(']', true)) {
      if (lex_.peek().kind == TokenKind::kEnd) bad_value(field, type, "a value or ']'");
      parse_one(v, field);
    }
    return v;
  }

  Lexer lex_;
  const ReadOptions& options_;
  ReadResult& result_;
  std::unordered_map<std::string, NodePtr> defs_;
};

}  // namespace

bool is_vrml97_header(std::string_view header) {
  return header.starts_with("#VRML V2.0") || is_x3d_header(header);
}

bool is_x3d_header(std::string_view header) {
  return header.starts_with("#X3D V");
}

ReadResult read_vrml97(std::string_view text, const ReadOptions& options) {
  ReadResult result;
  Parser parser(text, options, result);
  parser.parse_file();
  return result;
}

ReadResult read_vrml97_file(const std::string& path, ReadOptions options) {
  options.source_name = path == "-" ? "<stdin>" : path;
  const FileBytes text(path);
  return read_vrml97(text.view(), options);
}

}  // namespace lodforge::vrml97
