// X3D XML writer: one pass over the scene graph building a pugixml document.
// Values the classic reader kept as text (untyped fields, PROTO interfaces
// and bodies, statements) are read again here: their tokens, or for a PROTO
// the classic reader on its interface (as a Script's declarations) and its
// body (with IS allowed).
#include "lodforge/io/vrml97/write_x3d_xml.h"

#include <fmt/format.h>

#include <cctype>
#include <map>
#include <pugixml.hpp>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/lexer.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/x3d_fields.h"

namespace lodforge::vrml97 {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// The tokens of classic-encoding text: words, quoted strings (quotes kept)
// and the brackets and braces; comments and commas left out.
std::vector<std::string_view> classic_tokens(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; };
  while (i < text.size()) {
    const char c = text[i];
    if (space(c)) {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else if (c == '"') {
      std::size_t end = i + 1;
      while (end < text.size() && text[end] != '"') end += text[end] == '\\' ? 2 : 1;
      end = std::min(end + 1, text.size());
      out.push_back(text.substr(i, end - i));
      i = end;
    } else if (c == '[' || c == ']' || c == '{' || c == '}') {
      out.push_back(text.substr(i++, 1));
    } else {
      std::size_t end = i;
      while (end < text.size() && !space(text[end]) && text[end] != '#' && text[end] != '"' &&
             text[end] != '[' && text[end] != ']' && text[end] != '{' && text[end] != '}')
        ++end;
      out.push_back(text.substr(i, end - i));
      i = end;
    }
  }
  return out;
}

// The index just past the bracket or brace closing the one at `open`
// (strings and comments skipped); npos if it is not closed.
std::size_t past_closing(std::string_view text, std::size_t open) {
  const char o = text[open], c = o == '[' ? ']' : '}';
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (text[i] == '#') {
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else if (text[i] == o) {
      ++depth;
    } else if (text[i] == c && --depth == 0) {
      return i + 1;
    }
  }
  return std::string_view::npos;
}

// True if `s`, an attribute of no known type, is read back as the one
// string it is: not empty, no white space the reader trims or an XML reader
// turns into spaces, not quoted, not numbers or booleans.
bool reads_as_one_string(std::string_view s) {
  if (s.empty() || s.front() == '"' || s.front() == ' ' || s.back() == ' ') return false;
  if (std::any_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
    return false;
  const auto words = classic_tokens(s);
  return !std::all_of(words.begin(), words.end(),
                      [](std::string_view w) { return is_number_token(w) || is_bool_token(w); });
}

// An untyped value kept as classic text, as an XML attribute value.
std::string xml_value(std::string_view raw, ValueShape shape) {
  std::vector<std::string_view> t = classic_tokens(raw);
  std::erase_if(t, [](std::string_view x) { return x == "[" || x == "]"; });
  const bool one_string = t.size() == 1 && t[0].starts_with('"');
  if (one_string && shape != ValueShape::kMFString) {
    std::string s = vrml1::detail::unquote(t[0]);
    // A value of no known type is read by its form: unquoted, it must read
    // back as this one string; else it stays quoted (read as a string list).
    if (shape != ValueShape::kUnknown || reads_as_one_string(s)) return s;
    return std::string(t[0]);
  }
  std::string out;
  for (const std::string_view x : t) {
    if (!out.empty()) out += ' ';
    if (x == "TRUE" || x == "FALSE")
      out += x == "TRUE" ? "true" : "false";
    else
      out += x;
  }
  return out;
}

// A typed value as an XML attribute value.
std::string xml_value(const FieldValue& v) {
  std::string out;
  auto sep = [&] {
    if (!out.empty()) out += ' ';
  };
  switch (v.type.kind) {
    case FieldKind::kBool:
      for (const std::int32_t b : v.ints) sep(), out += b ? "true" : "false";
      return out;
    case FieldKind::kLong:
      for (const std::int32_t i : v.ints) sep(), fmt::format_to(std::back_inserter(out), "{}", i);
      return out;
    case FieldKind::kUInt32:
    case FieldKind::kImage:
      for (std::size_t i = 0; i < v.ints.size(); ++i) {
        sep();
        if (v.type.kind == FieldKind::kImage && i < 3)
          fmt::format_to(std::back_inserter(out), "{}", v.ints[i]);
        else
          fmt::format_to(std::back_inserter(out), "{:#x}", static_cast<std::uint32_t>(v.ints[i]));
      }
      return out;
    case FieldKind::kString:
      if (!v.type.multi) return v.strings.empty() ? std::string() : v.strings.front();
      for (const std::string& s : v.strings) sep(), out += quote_classic(s);
      return out;
    case FieldKind::kEnum:
    case FieldKind::kBitMask:
      for (const std::string& s : v.strings) sep(), out += s;
      return out;
    default:
      for (const float f : v.floats) sep(), fmt::format_to(std::back_inserter(out), "{}", f);
      return out;
  }
}

// `name` as an XML element or attribute name; DataError if it cannot be
// one (VRML names allow characters XML names do not, such as '&').
const char* xml_name(const std::string& name, std::string_view what) {
  auto ok = [](unsigned char c, bool first) {
    return std::isalpha(c) || c == '_' || c >= 0x80 ||
           (!first && (std::isdigit(c) || c == '-' || c == '.'));
  };
  bool valid = !name.empty();
  for (std::size_t i = 0; valid && i < name.size(); ++i)
    valid = ok(static_cast<unsigned char>(name[i]), i == 0);
  if (!valid)
    throw DataError(fmt::format(
        "cannot write the {} '{}' in the X3D XML encoding: it is no XML name", what, name));
  return name.c_str();
}

std::string_view x3d_access(std::string_view access) {
  if (access == "field") return "initializeOnly";
  if (access == "exposedField") return "inputOutput";
  if (access == "eventIn") return "inputOnly";
  if (access == "eventOut") return "outputOnly";
  return access;
}

// A declaration's name "access TYPE name" split in three.
struct Declaration {
  std::string access, type, name;
};
Declaration declaration_of(std::string_view field_name) {
  const auto t = classic_tokens(field_name);
  if (t.size() != 3) return {};
  return {std::string(x3d_access(t[0])), std::string(t[1]), std::string(t[2])};
}

using ProtoTypes =
    std::map<std::string, std::map<std::string, std::string, std::less<>>, std::less<>>;

class XmlWriter {
 public:
  explicit XmlWriter(ProtoTypes& protos) : protos_(protos) {}

  void write_scene(const scene::Scene& s, pugi::xml_document& doc) {
    const std::string& h = s.header;
    if (!is_x3d_header(h))
      throw DataError(fmt::format(
          "cannot write a scene with header '{}' as X3D XML: make it X3D first", h.substr(0, 40)));
    const std::string version = h.substr(6, h.find(' ', 6) - 6);
    std::string profile = "Full";
    for (const auto& r : s.roots)
      if (r->statement && r->type == "PROFILE")
        profile = std::string(classic_tokens(r->raw_body).at(0));
    pugi::xml_node decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    pugi::xml_node x3d = doc.append_child("X3D");
    x3d.append_attribute("profile") = profile.c_str();
    x3d.append_attribute("version") = version.c_str();
    x3d.append_attribute("xmlns:xsd") = "http://www.w3.org/2001/XMLSchema-instance";
    x3d.append_attribute("xsd:noNamespaceSchemaLocation") =
        fmt::format("http://www.web3d.org/specifications/x3d-{}.xsd", version).c_str();
    pugi::xml_node head = x3d.append_child("head");
    pugi::xml_node body = x3d.append_child("Scene");
    for (const auto& r : s.roots)
      if (!head_statement(head, *r)) count_refs(r);
    for (const auto& r : s.roots)
      if (r->type != "PROFILE" || !r->statement)
        if (!(r->statement && (r->type == "COMPONENT" || r->type == "META" || r->type == "UNIT")))
          write_node(body, r, "");
    if (!head.first_child()) x3d.remove_child(head);
  }

  void write_roots(pugi::xml_node parent, const std::vector<NodePtr>& roots) {
    for (const auto& r : roots) count_refs(r);
    for (const auto& r : roots) write_node(parent, r, "");
  }

 private:
  // COMPONENT, META and UNIT into <head>; false for any other node.
  static bool head_statement(pugi::xml_node head, const Node& n) {
    if (!n.statement) return false;
    const auto t = classic_tokens(n.raw_body);
    if (n.type == "COMPONENT") {
      std::string all;
      for (const auto x : t) all += x;
      const std::size_t colon = all.rfind(':');  // the level follows the last
      pugi::xml_node c = head.append_child("component");
      c.append_attribute("name") = all.substr(0, colon).c_str();
      if (colon != std::string::npos) c.append_attribute("level") = all.substr(colon + 1).c_str();
      return true;
    }
    if (n.type == "META" && t.size() == 2) {
      pugi::xml_node m = head.append_child("meta");
      m.append_attribute("name") = vrml1::detail::unquote(t[0]).c_str();
      m.append_attribute("content") = vrml1::detail::unquote(t[1]).c_str();
      return true;
    }
    if (n.type == "UNIT" && t.size() == 3) {
      pugi::xml_node u = head.append_child("unit");
      u.append_attribute("category") = std::string(t[0]).c_str();
      u.append_attribute("name") = std::string(t[1]).c_str();
      u.append_attribute("conversionFactor") = std::string(t[2]).c_str();
      return true;
    }
    return n.type == "PROFILE";
  }

  void count_refs(const NodePtr& n) {
    if (!n || ++refs_[n.get()] > 1) return;
    if (!n->name.empty()) taken_.insert(n->name);
    for (const auto& f : n->fields)
      for (const auto& c : f.value.nodes) count_refs(c);
  }

  std::string unique_name(const std::string& base) {
    for (int i = 1;; ++i) {
      std::string name = fmt::format("{}_{}", base.empty() ? "lf" : base, i);
      if (!taken_.count(name)) return name;
    }
  }

  // ROUTE, IMPORT, EXPORT, PROTO and EXTERNPROTO (a top-level statement or
  // a statement field of a node body).
  void write_statement(pugi::xml_node parent, std::string_view type, std::string_view raw) {
    const auto t = classic_tokens(raw);
    auto split = [&](std::string_view dotted, pugi::xml_node e, const char* node,
                     const char* field) {
      const std::size_t dot = dotted.find('.');
      if (dot == std::string_view::npos)
        throw DataError(fmt::format("{} {}: expected NODE.FIELD, got '{}'", type, raw, dotted));
      e.append_attribute(node) = std::string(dotted.substr(0, dot)).c_str();
      e.append_attribute(field) = std::string(dotted.substr(dot + 1)).c_str();
    };
    if (type == "ROUTE" && t.size() == 3) {
      pugi::xml_node r = parent.append_child("ROUTE");
      split(t[0], r, "fromNode", "fromField");
      split(t[2], r, "toNode", "toField");
    } else if (type == "IMPORT" && !t.empty()) {
      pugi::xml_node i = parent.append_child("IMPORT");
      split(t[0], i, "inlineDEF", "importedDEF");
      if (t.size() == 3) i.append_attribute("AS") = std::string(t[2]).c_str();
    } else if (type == "EXPORT" && !t.empty()) {
      pugi::xml_node e = parent.append_child("EXPORT");
      e.append_attribute("localDEF") = std::string(t[0]).c_str();
      if (t.size() == 3) e.append_attribute("AS") = std::string(t[2]).c_str();
    } else if (type == "PROTO" || type == "EXTERNPROTO") {
      write_proto(parent, raw, type == "EXTERNPROTO");
    } else if (type != "PROFILE" && type != "COMPONENT" && type != "META" && type != "UNIT") {
      throw DataError(fmt::format("cannot write the statement {} {} as X3D XML", type, raw));
    }
  }

  void write_proto(pugi::xml_node parent, std::string_view raw, bool external) {
    const std::string what =
        fmt::format("{} {}", external ? "EXTERNPROTO" : "PROTO", classic_tokens(raw).at(0));
    const std::size_t open = raw.find('[');
    const std::size_t close = open == std::string_view::npos ? open : past_closing(raw, open);
    if (close == std::string_view::npos)
      throw DataError(fmt::format("cannot write {} as X3D XML: no interface", what));
    const std::string name(classic_tokens(raw.substr(0, open)).at(0));
    const std::string_view interface = raw.substr(open + 1, close - open - 2);
    auto& types = protos_[name];
    pugi::xml_node p = parent.append_child(external ? "ExternProtoDeclare" : "ProtoDeclare");
    p.append_attribute("name") = name.c_str();
    if (external) {
      const auto t = classic_tokens(interface);
      for (std::size_t i = 0; i + 2 < t.size(); i += 3) {
        pugi::xml_node f = p.append_child("field");
        f.append_attribute("accessType") = std::string(x3d_access(t[i])).c_str();
        f.append_attribute("type") = std::string(t[i + 1]).c_str();
        f.append_attribute("name") = std::string(t[i + 2]).c_str();
        types[std::string(t[i + 2])] = std::string(t[i + 1]);
      }
      p.append_attribute("url") = xml_value(raw.substr(close), ValueShape::kMFString).c_str();
      return;
    }
    const std::size_t body_open = raw.find('{', close);
    const std::size_t body_close =
        body_open == std::string_view::npos ? body_open : past_closing(raw, body_open);
    if (body_close == std::string_view::npos)
      throw DataError(fmt::format("cannot write {} as X3D XML: no body", what));
    try {
      const ReadResult fields =
          read_vrml97(fmt::format("#X3D V3.2 utf8\nScript {{ {} \n}}", interface),
                      {.source_name = what + " interface"});
      pugi::xml_node i = p.append_child("ProtoInterface");
      XmlWriter nodes(protos_);
      for (const auto& f : fields.scene.roots.at(0)->fields) {
        declaration(i, f, nodes);
        types[declaration_of(f.name).name] = declaration_of(f.name).type;
      }
      const ReadResult body =
          read_vrml97(fmt::format("#X3D V3.2 utf8\n{}\n",
                                  raw.substr(body_open + 1, body_close - body_open - 2)),
                      {.source_name = what + " body", .proto_body = true});
      XmlWriter(protos_).write_roots(p.append_child("ProtoBody"), body.scene.roots);
    } catch (const ParseError& e) {
      throw DataError(
          fmt::format("cannot write {} as X3D XML: its text does not read: {}", what, e.what()));
    }
  }

  // A Script's, shader's or PROTO's interface declaration as a <field>.
  void declaration(pugi::xml_node parent, const scene::Field& f, XmlWriter& nodes) {
    const Declaration d = declaration_of(f.name);
    pugi::xml_node e = parent.append_child("field");
    e.append_attribute("accessType") = d.access.c_str();
    e.append_attribute("type") = d.type.c_str();
    e.append_attribute("name") = d.name.c_str();
    if (f.no_value || (f.is_raw && f.raw.starts_with("IS "))) return;
    if (f.is_raw) {
      e.append_attribute("value") = xml_value(f.raw, shape_of_type(d.type)).c_str();
      return;
    }
    for (const auto& c : f.value.nodes) nodes.count_refs(c);
    for (const auto& c : f.value.nodes) nodes.write_node(e, c, "");
  }

  void write_node(pugi::xml_node parent, const NodePtr& n, std::string_view field) {
    if (!n) return;
    if (n->statement) {
      write_statement(parent, n->type, n->raw_body);
      return;
    }
    if (n->is_raw)
      throw DataError(fmt::format("cannot write the node {} (kept as text) as X3D XML", n->type));
    const auto proto = protos_.find(n->type);
    const bool instance = proto != protos_.end();
    pugi::xml_node e =
        parent.append_child(instance ? "ProtoInstance" : xml_name(n->type, "node type"));
    if (instance) e.append_attribute("name") = n->type.c_str();
    const std::string_view default_field = instance ? "children" : default_container_field(n->type);
    auto container = [&] {
      if (!field.empty() && field != default_field)
        e.append_attribute("containerField") = std::string(field).c_str();
    };
    if (auto written = names_.find(n.get()); written != names_.end()) {
      e.append_attribute("USE") = written->second.c_str();
      container();
      return;
    }
    std::string name = n->name;
    if (refs_[n.get()] > 1) {
      if (name.empty() || shared_names_.count(name)) name = unique_name(name);
      shared_names_.insert(name);
      names_[n.get()] = name;
    }
    if (!name.empty()) {
      e.append_attribute("DEF") = name.c_str();
      taken_.insert(name);
    }
    container();
    write_fields(e, *n, instance ? &proto->second : nullptr);
  }

  void write_fields(pugi::xml_node e, const Node& n,
                    const std::map<std::string, std::string, std::less<>>* instance) {
    pugi::xml_node is;
    for (const auto& f : n.fields) {
      if (!f.is_raw || !f.raw.starts_with("IS ")) continue;
      if (!is) is = e.append_child("IS");
      pugi::xml_node c = is.append_child("connect");
      c.append_attribute("nodeField") =
          (f.name.find(' ') == std::string::npos ? f.name : declaration_of(f.name).name).c_str();
      c.append_attribute("protoField") = f.raw.substr(3).c_str();
    }
    // Interface declarations come first, as the XML encoding lists them.
    for (const auto& f : n.fields)
      if (f.name.find(' ') != std::string::npos) declaration(e, f, *this);
    std::vector<const scene::Field*> statements;
    for (const auto& f : n.fields) {
      if (f.is_raw && f.raw.starts_with("IS ") && f.name.find(' ') == std::string::npos) continue;
      if (f.name.find(' ') != std::string::npos) {
        continue;
      } else if (f.is_raw && (f.name == "ROUTE" || f.name == "PROTO" || f.name == "EXTERNPROTO" ||
                              f.name == "IMPORT" || f.name == "EXPORT")) {
        statements.push_back(&f);
      } else if (instance) {
        pugi::xml_node v = e.append_child("fieldValue");
        v.append_attribute("name") = f.name.c_str();
        const auto type = instance->find(f.name);
        if (!f.is_raw && f.value.type.kind == FieldKind::kNode)
          for (const auto& c : f.value.nodes) write_node(v, c, "");
        else
          v.append_attribute("value") =
              (f.is_raw ? xml_value(f.raw, type == instance->end() ? ValueShape::kUnknown
                                                                   : shape_of_type(type->second))
                        : xml_value(f.value))
                  .c_str();
      } else if (!f.is_raw && f.value.type.kind == FieldKind::kNode) {
        for (const auto& c : f.value.nodes) write_node(e, c, f.name);
      } else {
        e.append_attribute(xml_name(f.name, "field name")) =
            (f.is_raw ? xml_value(f.raw, x3d_value_shape(n.type, f.name)) : xml_value(f.value))
                .c_str();
      }
    }
    for (const scene::Field* f : statements) write_statement(e, f->name, f->raw);
  }

  ProtoTypes& protos_;
  std::unordered_map<const Node*, std::size_t> refs_;
  std::unordered_map<const Node*, std::string> names_;  // shared nodes written
  std::unordered_set<std::string> shared_names_;
  std::unordered_set<std::string> taken_;
};

struct StringSink : pugi::xml_writer {
  std::string text;
  void write(const void* data, std::size_t size) override {
    text.append(static_cast<const char*>(data), size);
  }
};

}  // namespace

std::string write_x3d_xml(const scene::Scene& scene) {
  pugi::xml_document doc;
  ProtoTypes protos;
  XmlWriter(protos).write_scene(scene, doc);
  StringSink sink;
  doc.save(sink, "  ", pugi::format_default, pugi::encoding_utf8);
  return std::move(sink.text);
}

void write_x3d_xml_file(const scene::Scene& scene, const std::string& path) {
  write_file_atomic(path, write_x3d_xml(scene));
}

}  // namespace lodforge::vrml97
