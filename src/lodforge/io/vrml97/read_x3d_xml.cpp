// X3D XML reader: the document rewritten in the classic encoding, then
// read by read_vrml97. Each line of the classic text remembers the XML
// position it came from (an element's or an attribute's), so an error found
// by the classic reader is reported at the XML's line and column.
//
// Decisions for real-world files:
//  | input                                   | what the reader does                        |
//  |-----------------------------------------|---------------------------------------------|
//  | attribute of a field whose type is known | written in its classic form (x3d_fields.h)  |
//  | other attribute                         | by its form: numbers (bracketed if over 4), |
//  |                                         | booleans, a quoted list (MFString), else one |
//  |                                         | string                                      |
//  | `class`, `id`, `xmlns...`, `a:b`        | left out (XML-only attributes)              |
//  | element without containerField          | fills its type's default field              |
//  | text or CDATA of a Script or shader     | appended to its url                         |
//  | `field` of the XML without a value      | the type's default value                    |
//  | XML comments, processing instructions   | left out                                    |
#include "lodforge/io/vrml97/read_x3d_xml.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <pugixml.hpp>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/lexer.h"
#include "lodforge/io/vrml97/x3d_fields.h"

namespace lodforge::vrml97 {
namespace {

struct Position {
  int line = 1;
  int col = 1;
};

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',';
}

std::vector<std::string_view> tokens(std::string_view v) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && is_space(v[i])) ++i;
    std::size_t end = i;
    while (end < v.size() && !is_space(v[end])) ++end;
    if (end > i) out.push_back(v.substr(i, end - i));
    i = end;
  }
  return out;
}

std::string_view trim(std::string_view v) {
  while (!v.empty() && is_space(v.front()) && v.front() != ',') v.remove_prefix(1);
  while (!v.empty() && is_space(v.back()) && v.back() != ',') v.remove_suffix(1);
  return v;
}

// A component's level: digits only (the writer finds it after the last colon).
bool is_level_token(std::string_view t) {
  return !t.empty() && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// A plain name (DEF, USE, a field or node type): none of the characters
// that end a word of the classic encoding, so it stays one word there.
bool is_word(std::string_view n) {
  if (n.empty()) return false;
  return std::none_of(n.begin(), n.end(), [](char c) {
    return vrml1::detail::is_delimiter(c) || c == '\'' || static_cast<unsigned char>(c) < 0x20;
  });
}

// Words the classic encoding reads as keywords, wherever they stand in a
// node's body: never a name there.
bool is_classic_keyword(std::string_view n) {
  static constexpr std::string_view kKeywords[] = {
      "AS",   "COMPONENT", "DEF",   "EXPORT", "EXTERNPROTO", "FALSE", "IMPORT", "IS", "META",
      "NULL", "PROFILE",   "PROTO", "ROUTE",  "TO",          "TRUE",  "UNIT",   "USE"};
  return std::find(std::begin(kKeywords), std::end(kKeywords), n) != std::end(kKeywords);
}

bool is_name(std::string_view n) {
  return is_word(n) && !is_number_token(n) && !is_classic_keyword(n);
}

// Nodes whose text content (or CDATA) is program code, taken as a url.
bool holds_code(std::string_view type) {
  return type == "Script" || type == "ShaderPart" || type == "ShaderProgram" ||
         type == "PackagedShader";
}

bool has_value_access(std::string_view access) {
  return access == "initializeOnly" || access == "inputOutput" || access == "field" ||
         access == "exposedField";
}

class Converter {
 public:
  Converter(std::string_view xml, const ReadOptions& options) : xml_(xml), options_(options) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < xml.size(); ++i)
      if (xml[i] == '\n') line_starts_.push_back(i + 1);
  }

  std::string run() {
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed =
        doc.load_buffer(xml_.data(), xml_.size(), pugi::parse_default, pugi::encoding_auto);
    if (!parsed) fail(parsed.offset, fmt::format("malformed XML: {}", parsed.description()));
    const pugi::xml_node root = doc.document_element();
    if (std::string_view(root.name()) != "X3D")
      fail(root ? root.offset_debug() : 0,
           fmt::format("expected the root element <X3D>, got <{}>", root.name()));
    const std::string_view version = root.attribute("version").as_string("3.0");
    if (version.empty() || !std::all_of(version.begin(), version.end(),
                                        [](char c) { return (c >= '0' && c <= '9') || c == '.'; }))
      fail(root.offset_debug(), fmt::format("expected a version such as 3.2, got '{}'", version));
    origin_.push_back(pos(root.offset_debug()));
    out_ = fmt::format("#X3D V{} utf8", version);
    if (const std::string_view profile = root.attribute("profile").as_string(); !profile.empty()) {
      line(root.offset_debug(), 0);
      out_ += fmt::format("PROFILE {}", checked_name(root, "profile", profile));
    }
    for (const pugi::xml_node part : root.children()) {
      if (part.type() != pugi::node_element) continue;
      const std::string_view name = part.name();
      if (name == "head") {
        for (const pugi::xml_node h : part.children())
          if (h.type() == pugi::node_element) head_statement(h);
      } else if (name == "Scene") {
        for (const pugi::xml_node e : part.children())
          if (e.type() == pugi::node_element) {
            line(e.offset_debug(), 0);
            item(e, 0, 0);
          }
      } else {
        fail(part.offset_debug(),
             fmt::format("expected <head> or <Scene> in <X3D>, got <{}>", name));
      }
    }
    out_ += '\n';
    return std::move(out_);
  }

  // The XML position the classic text's line `out_line` (1-based) came from.
  Position origin(int out_line) const {
    if (origin_.empty()) return {};
    const std::size_t i =
        std::clamp<std::size_t>(std::size_t(std::max(out_line, 1)) - 1, 0, origin_.size() - 1);
    return origin_[i];
  }

 private:
  Position pos(std::ptrdiff_t offset) const {
    const std::size_t o =
        std::size_t(std::clamp<std::ptrdiff_t>(offset, 0, std::ptrdiff_t(xml_.size())));
    const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), o) - 1;
    return {int(it - line_starts_.begin()) + 1, int(o - *it) + 1};
  }

  [[noreturn]] void fail(std::ptrdiff_t offset, const std::string& message) const {
    const Position p = pos(offset);
    throw ParseError(options_.source_name, p.line, p.col, message);
  }

  // The offset of attribute `name` of element `e` (its element's if not found).
  std::ptrdiff_t offset_of(const pugi::xml_node e, std::string_view name) const {
    const std::size_t from = std::size_t(std::max<std::ptrdiff_t>(e.offset_debug(), 0));
    const std::size_t end = xml_.find('>', from);
    for (std::size_t at = xml_.find(name, from); at < end && at != std::string_view::npos;
         at = xml_.find(name, at + 1)) {
      std::size_t after = at + name.size();
      while (after < xml_.size() && is_space(xml_[after])) ++after;
      if (at > 0 && is_space(xml_[at - 1]) && after < xml_.size() && xml_[after] == '=')
        return std::ptrdiff_t(at);
    }
    return e.offset_debug();
  }

  // Starts a classic line that came from XML offset `offset`, indented.
  void line(std::ptrdiff_t offset, int indent) {
    out_ += '\n';
    origin_.push_back(pos(offset));
    out_.append(std::size_t(indent) * 2, ' ');
  }

  // The line breaks of a string just written (a script's text) continue the
  // line it began on.
  void lines_within(std::string_view text) {
    for (const char c : text)
      if (c == '\n') origin_.push_back(origin_.back());
  }

  std::string_view checked_name(const pugi::xml_node e, std::string_view attribute,
                                std::string_view value) const {
    if (!is_name(value))
      fail(offset_of(e, attribute),
           fmt::format("expected a name for {} of <{}>, got '{}'", attribute, e.name(), value));
    return value;
  }

  // The value of `attribute` of `e`: a name, or with `number` a number.
  std::string_view required(const pugi::xml_node e, std::string_view attribute,
                            bool number = false) const {
    const pugi::xml_attribute a = e.attribute(std::string(attribute).c_str());
    if (!a) fail(e.offset_debug(), fmt::format("<{}> needs the attribute {}", e.name(), attribute));
    const std::string_view v = a.value();
    if (number && (!is_word(v) || !is_number_token(v)))
      fail(offset_of(e, attribute),
           fmt::format("expected a number for {} of <{}>, got '{}'", attribute, e.name(), v));
    return number ? v : checked_name(e, attribute, v);
  }

  void head_statement(const pugi::xml_node h) {
    const std::string_view name = h.name();
    line(h.offset_debug(), 0);
    if (name == "component") {
      const std::string_view level = required(h, "level", true);
      if (!is_level_token(level))
        fail(offset_of(h, "level"),
             fmt::format("expected a whole number for level of <component>, got '{}'", level));
      out_ += fmt::format("COMPONENT {}:{}", required(h, "name"), level);
    } else if (name == "meta") {
      out_ += fmt::format("META {} {}", quote_classic(h.attribute("name").as_string()),
                          quote_classic(h.attribute("content").as_string()));
    } else if (name == "unit") {
      out_ += fmt::format("UNIT {} {} {}", required(h, "category"), required(h, "name"),
                          required(h, "conversionFactor", true));
    } else {
      fail(h.offset_debug(),
           fmt::format("expected <component>, <meta> or <unit> in <head>, got <{}>", name));
    }
  }

  // A node or a statement, written where the classic text stands.
  void item(const pugi::xml_node e, int depth, int indent) {
    if (depth >= options_.max_depth)
      fail(e.offset_debug(),
           fmt::format("elements nested deeper than {} levels", options_.max_depth));
    const std::string_view name = e.name();
    if (name == "ROUTE") {
      out_ += fmt::format("ROUTE {}.{} TO {}.{}", required(e, "fromNode"), required(e, "fromField"),
                          required(e, "toNode"), required(e, "toField"));
    } else if (name == "IMPORT") {
      out_ += fmt::format("IMPORT {}.{}", required(e, "inlineDEF"), required(e, "importedDEF"));
      if (e.attribute("AS")) out_ += fmt::format(" AS {}", required(e, "AS"));
    } else if (name == "EXPORT") {
      out_ += fmt::format("EXPORT {}", required(e, "localDEF"));
      if (e.attribute("AS")) out_ += fmt::format(" AS {}", required(e, "AS"));
    } else if (name == "ProtoDeclare") {
      proto_declare(e, depth, indent);
    } else if (name == "ExternProtoDeclare") {
      extern_proto(e, indent);
    } else if (name == "ProtoInstance") {
      node(e, required(e, "name"), depth, indent);
    } else if (name == "IS" || name == "connect" || name == "field" || name == "fieldValue" ||
               name == "ProtoInterface" || name == "ProtoBody" || name == "head" ||
               name == "Scene" || name == "X3D") {
      fail(e.offset_debug(), fmt::format("<{}> is not allowed here", name));
    } else {
      node(e, checked_name(e, "element name", name), depth, indent);
    }
  }

  static bool is_statement(std::string_view name) {
    return name == "ROUTE" || name == "IMPORT" || name == "EXPORT" || name == "ProtoDeclare" ||
           name == "ExternProtoDeclare";
  }

  // The field of its parent element `e` fills.
  static std::string container_of(const pugi::xml_node e) {
    if (const pugi::xml_attribute cf = e.attribute("containerField")) return cf.value();
    const std::string_view name = e.name();
    return std::string(name == "ProtoInstance" ? "children" : default_container_field(name));
  }

  // A node element (a ProtoInstance too, `type` its prototype's name).
  void node(const pugi::xml_node e, std::string_view type, int depth, int indent) {
    if (const pugi::xml_attribute use = e.attribute("USE")) {
      out_ += fmt::format("USE {}", checked_name(e, "USE", use.value()));
      return;
    }
    if (const pugi::xml_attribute def = e.attribute("DEF"))
      out_ += fmt::format("DEF {} ", checked_name(e, "DEF", def.value()));
    out_ += type;
    out_ += " {";
    const bool instance = std::string_view(e.name()) == "ProtoInstance";
    std::map<std::string, std::string, std::less<>> connects;  // nodeField -> protoField
    for (const pugi::xml_node is : e.children("IS"))
      for (const pugi::xml_node c : is.children("connect"))
        connects[std::string(required(c, "nodeField"))] = std::string(required(c, "protoField"));
    // Text in any other node is not part of the scene (19776-1 maps none).
    const std::string text = !instance && holds_code(type) ? script_text(e) : std::string();
    for (const pugi::xml_attribute a : e.attributes()) {
      const std::string_view name = a.name();
      if (name == "DEF" || name == "USE" || name == "containerField" || name == "class" ||
          name == "id" || name.starts_with("xmlns") || name.find(':') != std::string_view::npos ||
          (instance && name == "name"))
        continue;
      const std::ptrdiff_t at = offset_of(e, name);
      line(at, indent + 1);
      out_ += checked_name(e, "attribute name", name);
      out_ += ' ';
      const std::string value = classic_value(x3d_value_shape(type, name), a.value(), at, name);
      if (name == "url" && !text.empty()) {
        out_ += fmt::format("[ {} {} ]", strip_brackets(value), quote_classic(text));
        lines_within(text);
      } else {
        out_ += value;
      }
    }
    if (!text.empty() && !e.attribute("url")) {
      line(e.offset_debug(), indent + 1);
      out_ += fmt::format("url {}", quote_classic(text));
      lines_within(text);
    }
    std::vector<std::pair<std::string, std::vector<pugi::xml_node>>> groups;
    for (const pugi::xml_node c : e.children()) {
      if (c.type() != pugi::node_element) continue;
      const std::string_view name = c.name();
      if (name == "IS") continue;
      const bool declaration = name == "field", value = name == "fieldValue" && instance;
      if (declaration || value || is_statement(name)) {
        line(c.offset_debug(), indent + 1);
        if (declaration)
          field_declaration(c, true, connects, depth, indent + 1);
        else if (value)
          field_value(c, type, depth, indent + 1);
        else
          item(c, depth + 1, indent + 1);
      } else {
        const std::string field = container_of(c);
        auto g = std::find_if(groups.begin(), groups.end(),
                              [&](const auto& p) { return p.first == field; });
        if (g == groups.end())
          groups.push_back({field, {c}});
        else
          g->second.push_back(c);
      }
    }
    for (const auto& [field, nodes] : groups) {
      line(nodes.front().offset_debug(), indent + 1);
      out_ += checked_name(nodes.front(), "containerField", field);
      node_list(nodes, depth, indent + 1);
    }
    for (const auto& [field, proto_field] : connects) {
      line(e.offset_debug(), indent + 1);
      out_ += fmt::format("{} IS {}", field, proto_field);
    }
    out_ += " }";
  }

  // ` node` for one, ` [ nodes ]` for several.
  void node_list(const std::vector<pugi::xml_node>& nodes, int depth, int indent) {
    if (nodes.size() == 1) {
      out_ += ' ';
      item(nodes.front(), depth + 1, indent);
      return;
    }
    out_ += " [";
    for (const pugi::xml_node n : nodes) {
      line(n.offset_debug(), indent + 1);
      item(n, depth + 1, indent + 1);
    }
    out_ += " ]";
  }

  static std::string_view strip_brackets(std::string_view v) {
    v = trim(v);
    if (v.size() >= 2 && v.front() == '[' && v.back() == ']') v = trim(v.substr(1, v.size() - 2));
    return v;
  }

  // The text (or CDATA) content of a Script or shader element: its code.
  static std::string script_text(const pugi::xml_node e) {
    std::string text;
    for (const pugi::xml_node c : e.children())
      if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) text += c.value();
    return trim(text).empty() ? std::string() : text;
  }

  // The classic form of an XML attribute value of the given shape.
  std::string classic_value(ValueShape shape, std::string_view value, std::ptrdiff_t at,
                            std::string_view field) const {
    const std::string_view v = trim(value);
    switch (shape) {
      case ValueShape::kSFString:
        return quote_classic(value);
      case ValueShape::kMFString:
        if (v.empty()) return "[]";
        return v.front() == '"' ? fmt::format("[ {} ]", v) : quote_classic(value);
      case ValueShape::kNode:
        fail(at, fmt::format("field '{}' holds nodes: give them as child elements", field));
      case ValueShape::kSFNumbers:
      case ValueShape::kMFNumbers: {
        // Not numbers after all (a field of another node, or a prototype's,
        // by the same name): by its form, as an unknown one; a typed field
        // then gets the classic reader's error at this attribute.
        const auto t = tokens(v);
        if (!t.empty() && std::all_of(t.begin(), t.end(), [](auto x) {
              return is_number_token(x) || is_bool_token(x);
            }))
          return numbers(v, shape == ValueShape::kMFNumbers, at, field);
        break;
      }
      case ValueShape::kUnknown:
        break;
    }
    if (v.empty()) return "[]";
    if (v.front() == '"') return fmt::format("[ {} ]", v);
    const auto t = tokens(v);
    // Up to four numbers: a single value (SFVec3f, SFRotation, ...) of a
    // field no table names; more: a list.
    if (std::all_of(t.begin(), t.end(),
                    [](auto x) { return is_number_token(x) || is_bool_token(x); }))
      return numbers(v, t.size() > 4 || (t.size() > 1 && is_bool_token(t[0])), at, field);
    return quote_classic(value);
  }

  // Numbers and booleans (true/false made TRUE/FALSE), bracketed for a list.
  std::string numbers(std::string_view v, bool list, std::ptrdiff_t at,
                      std::string_view field) const {
    std::string out = list ? "[ " : "";
    for (const std::string_view t : tokens(v)) {
      if (t == "true" || t == "TRUE")
        out += "TRUE";
      else if (t == "false" || t == "FALSE")
        out += "FALSE";
      else if (is_number_token(t))
        out += t;
      else
        fail(at, fmt::format("expected numbers for field '{}', got '{}'", field, t));
      out += ' ';
    }
    if (list)
      out += "]";
    else if (!out.empty())
      out.pop_back();
    if (out.empty()) fail(at, fmt::format("expected a value for field '{}'", field));
    return out;
  }

  // `access TYPE name [value | IS protoField]` from a <field> element.
  void field_declaration(const pugi::xml_node f, bool with_value,
                         std::map<std::string, std::string, std::less<>>& connects, int depth,
                         int indent) {
    std::string_view access = required(f, "accessType");
    const std::string_view type = required(f, "type");
    const std::string_view name = required(f, "name");
    if (shape_of_type(type) == ValueShape::kUnknown)
      fail(offset_of(f, "type"), fmt::format("unknown field type '{}'", type));
    out_ += fmt::format("{} {} {}", access, type, name);
    if (auto c = connects.find(name); c != connects.end()) {
      out_ += fmt::format(" IS {}", c->second);
      connects.erase(c);
      return;
    }
    if (!with_value || !has_value_access(access)) return;
    if (shape_of_type(type) == ValueShape::kNode) {
      std::vector<pugi::xml_node> nodes;
      for (const pugi::xml_node c : f.children())
        if (c.type() == pugi::node_element) nodes.push_back(c);
      if (nodes.empty())
        out_ += type.starts_with("MF") ? " []" : " NULL";
      else
        node_list(nodes, depth, indent);
      return;
    }
    const pugi::xml_attribute value = f.attribute("value");
    out_ += ' ';
    out_ += value ? classic_value(shape_of_type(type), value.value(), offset_of(f, "value"), name)
                  : default_classic_value(type);
  }

  // `name value` of a ProtoInstance, typed by its prototype's interface.
  void field_value(const pugi::xml_node f, std::string_view proto, int depth, int indent) {
    const std::string_view name = required(f, "name");
    out_ += name;
    std::vector<pugi::xml_node> nodes;
    for (const pugi::xml_node c : f.children())
      if (c.type() == pugi::node_element) nodes.push_back(c);
    if (!nodes.empty()) {
      node_list(nodes, depth, indent);
      return;
    }
    std::string_view type;
    if (auto p = proto_fields_.find(proto); p != proto_fields_.end())
      if (auto t = p->second.find(name); t != p->second.end()) type = t->second;
    const ValueShape shape = shape_of_type(type);
    if (shape == ValueShape::kNode || (shape == ValueShape::kUnknown && !f.attribute("value"))) {
      out_ += type.starts_with("MF") ? " []" : " NULL";  // no node given
      return;
    }
    out_ += ' ';
    out_ += classic_value(shape, f.attribute("value").as_string(), offset_of(f, "value"), name);
  }

  void proto_declare(const pugi::xml_node e, int depth, int indent) {
    const std::string name(required(e, "name"));
    out_ += fmt::format("PROTO {} [", name);
    auto& types = proto_fields_[name];
    std::map<std::string, std::string, std::less<>> no_connects;
    for (const pugi::xml_node f : e.child("ProtoInterface").children("field")) {
      line(f.offset_debug(), indent + 1);
      field_declaration(f, true, no_connects, depth, indent + 1);
      types[f.attribute("name").value()] = f.attribute("type").value();
    }
    line(e.offset_debug(), indent);
    out_ += "] {";
    for (const pugi::xml_node c : e.child("ProtoBody").children())
      if (c.type() == pugi::node_element) {
        line(c.offset_debug(), indent + 1);
        item(c, depth + 1, indent + 1);
      }
    out_ += " }";
  }

  void extern_proto(const pugi::xml_node e, int indent) {
    const std::string name(required(e, "name"));
    out_ += fmt::format("EXTERNPROTO {} [", name);
    auto& types = proto_fields_[name];
    std::map<std::string, std::string, std::less<>> no_connects;
    for (const pugi::xml_node f : e.children("field")) {
      line(f.offset_debug(), indent + 1);
      field_declaration(f, false, no_connects, 0, indent + 1);
      types[f.attribute("name").value()] = f.attribute("type").value();
    }
    out_ += " ] ";
    out_ += classic_value(ValueShape::kMFString, e.attribute("url").as_string(),
                          offset_of(e, "url"), "url");
  }

  std::string_view xml_;
  const ReadOptions& options_;
  std::vector<std::size_t> line_starts_;
  std::string out_;
  std::vector<Position> origin_;
  std::map<std::string, std::map<std::string, std::string, std::less<>>, std::less<>> proto_fields_;
};

}  // namespace

bool is_x3d_xml_path(std::string_view path) {
  auto ends = [&](std::string_view e) {
    return path.size() >= e.size() &&
           std::equal(
               e.begin(), e.end(), path.end() - std::ptrdiff_t(e.size()),
               [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
  };
  return ends(".x3d") || ends(".x3d.gz") || ends(".x3dz");
}

std::string x3d_xml_to_classic(std::string_view xml, const ReadOptions& options) {
  return Converter(xml, options).run();
}

ReadResult read_x3d_xml(std::string_view xml, const ReadOptions& options) {
  Converter converter(xml, options);
  const std::string text = converter.run();
  try {
    return read_vrml97(text, options);
  } catch (const ParseError& e) {
    const Position p = converter.origin(e.line());
    std::string message = e.what();
    const std::string prefix = fmt::format("{}:{}:{}: ", e.file(), e.line(), e.column());
    if (message.starts_with(prefix)) message.erase(0, prefix.size());
    throw ParseError(options.source_name, p.line, p.col, message);
  }
}

ReadResult read_x3d_xml_file(const std::string& path, ReadOptions options) {
  options.source_name = path == "-" ? "<stdin>" : path;
  const FileBytes text(path);
  return read_x3d_xml(text.view(), options);
}

}  // namespace lodforge::vrml97
