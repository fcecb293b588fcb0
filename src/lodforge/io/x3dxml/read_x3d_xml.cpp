// X3D XML reader: the document restated in the classic encoding and parsed by
// read_vrml97, so both encodings give one scene model (a PROTO body, kept
// verbatim, is classic text either way).
//
// Decisions for real-world files:
//  | input                                  | what the reader does                         |
//  |----------------------------------------|----------------------------------------------|
//  | malformed XML                          | error at pugixml's offset (line:column)      |
//  | root element other than <X3D>          | error                                        |
//  | several numbers in an attribute        | MF value (brackets) unless a known SF vector |
//  | attribute that is not numbers/booleans | a string: quoted, unless it already is       |
//  | class / id / style / xmlns attributes  | dropped (HTML-page attributes, no field)     |
//  | XML comments, processing instructions  | dropped                                      |
//  | text or CDATA in Script / ShaderPart   | one more url string                          |
#include "lodforge/io/x3dxml/read_x3d_xml.h"

#include <fmt/format.h>

#include <cctype>
#include <functional>
#include <map>
#include <pugixml.hpp>
#include <unordered_set>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/x3dxml/x3d_fields.h"

namespace lodforge::x3dxml {
namespace {

using detail::default_container;

// A classic string literal holding `s`.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
  return out;
}

bool is_number(std::string_view w) {
  if (w.empty()) return false;
  const char c = w[0];
  if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.'))
    return false;
  return std::all_of(w.begin(), w.end(), [](char d) {
    return std::isalnum(static_cast<unsigned char>(d)) || d == '-' || d == '+' || d == '.';
  });
}

// The whitespace- and comma-separated words of an attribute value.
std::vector<std::string_view> words(std::string_view v) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && (std::isspace(static_cast<unsigned char>(v[i])) || v[i] == ',')) ++i;
    std::size_t end = i;
    while (end < v.size() && !std::isspace(static_cast<unsigned char>(v[end])) && v[end] != ',')
      ++end;
    if (end > i) out.push_back(v.substr(i, end - i));
    i = end;
  }
  return out;
}

// Number of classic string literals in `v` (which starts with a quote).
std::size_t string_count(std::string_view v) {
  std::size_t n = 0;
  bool in = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (in && v[i] == '\\') {
      ++i;
      continue;
    }
    if (v[i] == '"') {
      if (!in) ++n;
      in = !in;
    }
  }
  return n;
}

// What an attribute holds when its type is known (interface declarations,
// fieldValues of a declared prototype).
struct KnownType {
  bool known = false;
  bool multi = false;
  bool string = false;
};

KnownType known_type(std::string_view type_name) {
  KnownType k;
  if (type_name.size() < 3) return k;
  k.known = true;
  k.multi = type_name[0] == 'M';
  k.string = type_name.substr(2) == "String";
  return k;
}

// An attribute value in the classic encoding.
std::string classic_value(std::string_view parent, std::string_view field, std::string_view v,
                          KnownType type = {}) {
  std::size_t b = 0;
  while (b < v.size() && std::isspace(static_cast<unsigned char>(v[b]))) ++b;
  std::string_view t = v.substr(b);
  const bool sf_string =
      type.known ? type.string && !type.multi : detail::single_string_field(parent, field);
  if (sf_string) return quoted(v);
  if (!t.empty() && t[0] == '"')
    return string_count(t) > 1 ? fmt::format("[ {} ]", t) : std::string(t);
  const auto ws = words(t);
  if (type.known && type.string) return ws.empty() ? "[]" : quoted(v);
  if (ws.empty()) return "[]";
  bool numeric = true;
  for (auto w : ws)
    numeric =
        numeric && (is_number(w) || w == "true" || w == "false" || w == "TRUE" || w == "FALSE");
  if (!numeric) return quoted(v);
  std::string out;
  for (auto w : ws) {
    if (!out.empty()) out += ' ';
    out += w == "true" ? "TRUE" : w == "false" ? "FALSE" : std::string(w);
  }
  const bool multi =
      type.known ? type.multi : ws.size() > 1 && !detail::single_vector_field(parent, field);
  return multi ? "[ " + out + " ]" : out;
}

bool is_statement_element(std::string_view n) {
  return n == "ROUTE" || n == "IMPORT" || n == "EXPORT" || n == "ProtoDeclare" ||
         n == "ExternProtoDeclare";
}

bool skipped_attribute(std::string_view name) {
  return name == "DEF" || name == "USE" || name == "containerField" || name == "class" ||
         name == "id" || name == "style" || name.starts_with("xmlns") || name.starts_with("xsd:");
}

class Converter {
 public:
  Converter(std::string_view text, std::string source, int max_depth)
      : text_(text), source_(std::move(source)), max_depth_(max_depth) {}

  std::string convert() {
    pugi::xml_document doc;
    const pugi::xml_parse_result r =
        doc.load_buffer(text_.data(), text_.size(),
                        pugi::parse_default | pugi::parse_ws_pcdata_single, pugi::encoding_utf8);
    if (!r)
      fail(static_cast<std::size_t>(r.offset), fmt::format("malformed XML: {}", r.description()));
    pugi::xml_node x3d = doc.document_element();
    if (std::string_view(x3d.name()) != "X3D")
      fail(x3d, fmt::format("expected an <X3D> document, got <{}>", x3d.name()));
    std::string version = x3d.attribute("version").as_string("3.0");
    if (version.empty() || !std::all_of(version.begin(), version.end(), [](char c) {
          return std::isdigit((unsigned char)c) || c == '.';
        }))
      fail(x3d, fmt::format("bad X3D version '{}'", version));
    out_ = "#X3D V" + version + " utf8";
    if (const auto p = x3d.attribute("profile")) line(x3d, fmt::format("PROFILE {}", p.value()));
    for (pugi::xml_node e : x3d.children("head"))
      for (pugi::xml_node h : e.children()) head_statement(h);
    for (pugi::xml_node s : x3d.children("Scene"))
      for (pugi::xml_node e : s.children()) element(e, "", 0);
    out_ += '\n';
    return std::move(out_);
  }

  // The XML position of classic line `classic_line` (1-based).
  std::pair<int, int> position_of_line(int classic_line) const {
    if (classic_line < 1 || lines_.empty()) return {1, 1};
    const std::size_t i = std::min<std::size_t>(classic_line - 1, lines_.size() - 1);
    return position(lines_[i]);
  }

  [[noreturn]] void fail(std::size_t offset, const std::string& message) const {
    const auto [l, c] = position(offset);
    throw ParseError(source_, l, c, message);
  }

 private:
  [[noreturn]] void fail(pugi::xml_node at, const std::string& message) const {
    fail(start_of(at), message);
  }

  // Where element `at` starts: pugixml's offset is that of its name, after '<'.
  static std::size_t start_of(pugi::xml_node at) {
    const std::ptrdiff_t o = at.offset_debug();
    return static_cast<std::size_t>(std::max<std::ptrdiff_t>(o - 1, 0));
  }

  std::pair<int, int> position(std::size_t offset) const {
    offset = std::min(offset, text_.size());
    int l = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset; ++i)
      if (text_[i] == '\n') {
        ++l;
        line_start = i + 1;
      }
    return {l, static_cast<int>(offset - line_start) + 1};
  }

  // Starts a classic line for XML node `at`.
  void line(pugi::xml_node at, std::string_view text) {
    out_ += '\n';
    lines_.push_back(start_of(at));
    out_ += text;
  }

  void head_statement(pugi::xml_node h) {
    const std::string_view n = h.name();
    if (n == "component")
      line(h, fmt::format("COMPONENT {}:{}", h.attribute("name").value(),
                          h.attribute("level").as_string("1")));
    else if (n == "unit")
      line(h, fmt::format("UNIT {} {} {}", h.attribute("category").value(),
                          h.attribute("name").value(),
                          h.attribute("conversionFactor").as_string("1")));
    else if (n == "meta")
      line(h, fmt::format("META {} {}", quoted(h.attribute("name").value()),
                          quoted(h.attribute("content").value())));
  }

  // Field and node type names are identifiers in both encodings.
  void check_name(pugi::xml_node e, std::string_view name) {
    const bool ok = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                    });
    if (!ok) fail(e, fmt::format("'{}' is not an X3D node or field name", name));
  }

  std::string_view need(pugi::xml_node e, const char* attribute) {
    const pugi::xml_attribute a = e.attribute(attribute);
    if (!a || !*a.value())
      fail(e, fmt::format("<{}> without the attribute {}", e.name(), attribute));
    return a.value();
  }

  // A statement element; false if `e` is none.
  bool statement(pugi::xml_node e, int depth) {
    const std::string_view n = e.name();
    if (n == "ROUTE") {
      const std::string_view from_node = need(e, "fromNode");
      const std::string_view from_field = need(e, "fromField");
      const std::string_view to_node = need(e, "toNode");
      const std::string_view to_field = need(e, "toField");
      line(e, fmt::format("ROUTE {}.{} TO {}.{}", from_node, from_field, to_node, to_field));
    } else if (n == "IMPORT") {
      const std::string_view inline_def = need(e, "inlineDEF");
      std::string s = fmt::format("IMPORT {}.{}", inline_def, need(e, "importedDEF"));
      if (*e.attribute("AS").value()) s += fmt::format(" AS {}", e.attribute("AS").value());
      line(e, s);
    } else if (n == "EXPORT") {
      std::string s = fmt::format("EXPORT {}", need(e, "localDEF"));
      if (*e.attribute("AS").value()) s += fmt::format(" AS {}", e.attribute("AS").value());
      line(e, s);
    } else if (n == "ProtoDeclare" || n == "ExternProtoDeclare") {
      proto(e, depth);
    } else {
      return false;
    }
    return true;
  }

  // An interface declaration (<field> of a prototype, Script or shader).
  void declaration(pugi::xml_node f, std::string_view parent, const std::string& is, int depth,
                   bool with_value) {
    const std::string_view access = need(f, "accessType");
    const std::string_view type = need(f, "type");
    const std::string_view name = need(f, "name");
    line(f, fmt::format("{} {} {}", access, type, name));
    if (!is.empty()) {
      out_ += " IS " + is;
      return;
    }
    if (!with_value || access == "inputOnly" || access == "outputOnly") return;
    if (type == "SFNode" || type == "MFNode") {
      node_list(f, parent, type == "MFNode", depth);
      return;
    }
    const pugi::xml_attribute v = f.attribute("value");
    out_ += ' ';
    if (v)
      out_ += classic_value(parent, name, v.value(), known_type(type));
    else
      out_ += known_type(type).multi ? "[]" : default_value(type);
  }

  static std::string default_value(std::string_view type) {
    const std::string_view base = type.substr(2);
    if (base == "Bool") return "FALSE";
    if (base == "String") return "\"\"";
    if (base == "Vec2f" || base == "Vec2d") return "0 0";
    if (base == "Vec3f" || base == "Vec3d" || base == "Color") return "0 0 0";
    if (base == "Rotation") return "0 0 1 0";
    if (base == "ColorRGBA" || base == "Vec4f" || base == "Vec4d") return "0 0 0 0";
    if (base == "Image") return "0 0 0";
    return "0";
  }

  // The node children of `e` as the value of an SFNode / MFNode field.
  void node_list(pugi::xml_node e, std::string_view parent, bool multi, int depth) {
    std::vector<pugi::xml_node> nodes;
    for (pugi::xml_node c : e.children())
      if (c.type() == pugi::node_element && std::string_view(c.name()) != "IS") nodes.push_back(c);
    emit_nodes(nodes, multi || nodes.size() > 1, depth);
    (void)parent;
  }

  void emit_nodes(const std::vector<pugi::xml_node>& nodes, bool bracket, int depth) {
    if (nodes.empty()) {
      out_ += bracket ? " []" : " NULL";
      return;
    }
    if (bracket) out_ += " [";
    for (pugi::xml_node c : nodes) element(c, "", depth + 1);
    if (bracket) out_ += " ]";
  }

  void proto(pugi::xml_node e, int depth) {
    const bool external = std::string_view(e.name()) == "ExternProtoDeclare";
    const std::string_view name = need(e, "name");
    line(e, fmt::format("{} {} [", external ? "EXTERNPROTO" : "PROTO", name));
    auto& fields = protos_[std::string(name)];
    pugi::xml_node interface = external ? e : e.child("ProtoInterface");
    for (pugi::xml_node f : interface.children("field")) {
      declaration(f, "", "", depth, !external);
      fields[f.attribute("name").value()] = f.attribute("type").value();
    }
    out_ += " ]";
    if (external) {
      out_ += ' ' + classic_value("", "url", e.attribute("url").value(), known_type("MFString"));
      return;
    }
    out_ += " {";
    for (pugi::xml_node c : e.child("ProtoBody").children()) element(c, "", depth + 1);
    out_ += " }";
  }

  // A node or statement element (`parent` is the type holding it, "" at top level).
  void element(pugi::xml_node e, std::string_view parent, int depth) {
    if (e.type() != pugi::node_element) return;
    if (depth >= max_depth_)
      fail(e, fmt::format("elements nested deeper than {} levels", max_depth_));
    if (statement(e, depth)) return;
    const std::string_view n = e.name();
    if (n == "IS" || n == "field" || n == "fieldValue" || n == "connect" || n == "head" ||
        n == "ProtoInterface" || n == "ProtoBody")
      fail(e, fmt::format("<{}> out of place", n));
    (void)parent;
    if (const auto use = e.attribute("USE")) {
      line(e, fmt::format("USE {}", use.value()));
      return;
    }
    check_name(e, n);
    std::string type(n);
    const bool instance = n == "ProtoInstance";
    if (instance) type = need(e, "name");
    std::string start;
    if (const auto def = e.attribute("DEF")) start = fmt::format("DEF {} ", def.value());
    line(e, start + type + " {");
    body(e, type, instance, depth);
    out_ += " }";
  }

  void body(pugi::xml_node e, const std::string& type, bool instance, int depth) {
    std::map<std::string, std::string> is;  // node field -> prototype field
    for (pugi::xml_node c : e.children("IS"))
      for (pugi::xml_node k : c.children("connect"))
        is[need(k, "nodeField").data()] = need(k, "protoField");
    std::string cdata;
    for (pugi::xml_node c : e.children())
      if (c.type() == pugi::node_cdata || c.type() == pugi::node_pcdata) cdata += c.value();
    const bool has_source = !std::all_of(cdata.begin(), cdata.end(), [](char c) {
      return std::isspace(static_cast<unsigned char>(c));
    });
    for (pugi::xml_attribute a : e.attributes()) {
      const std::string_view an = a.name();
      if (skipped_attribute(an) || (instance && an == "name")) continue;
      if (is.count(std::string(an))) continue;
      if (has_source && an == "url") continue;
      check_name(e, an);
      line(e, fmt::format("{} {}", an, classic_value(type, an, a.value())));
    }
    // Child elements by the field they go to, in order of first appearance.
    std::vector<std::pair<std::string, std::vector<pugi::xml_node>>> groups;
    auto flush = [&] {
      for (const auto& [field, nodes] : groups) {
        line(nodes.front(), field);
        emit_nodes(nodes, nodes.size() > 1 || !detail::single_node_field(type, field), depth);
      }
      groups.clear();
    };
    for (pugi::xml_node c : e.children()) {
      if (c.type() != pugi::node_element) continue;
      const std::string_view cn = c.name();
      if (cn == "IS") continue;
      // Fields before a declaration or statement stay before it.
      if (cn == "field" || cn == "fieldValue" || is_statement_element(cn)) flush();
      if (cn == "field") {
        const std::string fname = c.attribute("name").value();
        const auto it = is.find(fname);
        declaration(c, type, it == is.end() ? "" : it->second, depth, true);
        if (it != is.end()) is.erase(it);
        continue;
      }
      if (instance && cn == "fieldValue") {
        field_value(c, type, depth);
        continue;
      }
      if (statement(c, depth)) continue;
      std::string field = c.attribute("containerField").value();
      if (field.empty()) field = default_container(cn == "ProtoInstance" ? "" : cn, type);
      auto g = std::find_if(groups.begin(), groups.end(),
                            [&](const auto& p) { return p.first == field; });
      if (g == groups.end()) g = groups.insert(groups.end(), {field, {}});
      g->second.push_back(c);
    }
    flush();
    for (const auto& [field, proto_field] : is)
      line(e, fmt::format("{} IS {}", field, proto_field));
    if (has_source) {
      std::string url = e.attribute("url").value();
      std::size_t b = url.find_first_not_of(" \t\r\n");
      url = b == std::string::npos ? "" : url.substr(b);
      if (!url.empty() && url[0] != '"') url = quoted(url);
      line(e, fmt::format("url [ {} {} ]", url, quoted(cdata)));
    }
  }

  void field_value(pugi::xml_node f, const std::string& type, int depth) {
    const std::string_view name = need(f, "name");
    std::string ftype;
    if (const auto p = protos_.find(type); p != protos_.end())
      if (const auto t = p->second.find(std::string(name)); t != p->second.end()) ftype = t->second;
    line(f, std::string(name));
    const bool has_nodes =
        f.find_child([](pugi::xml_node c) { return c.type() == pugi::node_element; });
    if (ftype == "SFNode" || ftype == "MFNode" || (ftype.empty() && has_nodes)) {
      node_list(f, type, ftype == "MFNode", depth);
      return;
    }
    out_ += ' ' + classic_value(type, name, f.attribute("value").value(), known_type(ftype));
  }

  std::string_view text_;
  std::string source_;
  int max_depth_;
  std::string out_;
  std::vector<std::size_t> lines_;  // XML offset of each classic line after the header
  std::map<std::string, std::map<std::string, std::string>> protos_;  // name -> field -> type
};

// Node lines of the classic text as lines of the XML file.
void relocate_lines(scene::Scene& scene, const Converter& c) {
  std::unordered_set<const scene::Node*> done;
  std::function<void(const scene::NodePtr&)> walk = [&](const scene::NodePtr& n) {
    if (!n || !done.insert(n.get()).second) return;
    if (n->first_line > 0) n->first_line = c.position_of_line(n->first_line - 1).first;
    if (n->last_line > 0) n->last_line = c.position_of_line(n->last_line - 1).first;
    for (const auto& f : n->fields)
      for (const auto& k : f.value.nodes) walk(k);
  };
  for (const auto& r : scene.roots) walk(r);
}

}  // namespace

bool is_xml_start(std::string_view head) {
  if (head.starts_with("\xEF\xBB\xBF")) head.remove_prefix(3);
  while (!head.empty() && std::isspace(static_cast<unsigned char>(head.front())))
    head.remove_prefix(1);
  return head.starts_with("<?xml") || head.starts_with("<X3D") || head.starts_with("<!DOCTYPE");
}

std::string x3d_xml_to_classic(std::string_view text, const std::string& source_name) {
  return Converter(text, source_name, vrml97::ReadOptions{}.max_depth).convert();
}

vrml97::ReadResult read_x3d_xml(std::string_view text, const vrml97::ReadOptions& options) {
  Converter c(text, options.source_name, options.max_depth);
  const std::string classic = c.convert();
  vrml97::ReadOptions o = options;
  try {
    vrml97::ReadResult r = vrml97::read_vrml97(classic, o);
    relocate_lines(r.scene, c);
    return r;
  } catch (const ParseError& e) {
    // The classic line (header first) names the element that gave it.
    const std::string what = e.what();
    const std::string prefix = fmt::format("{}:{}:{}: ", e.file(), e.line(), e.column());
    const std::string message = what.starts_with(prefix) ? what.substr(prefix.size()) : what;
    const auto [l, col] = c.position_of_line(e.line() - 1);
    throw ParseError(options.source_name, l, col, message);
  }
}

vrml97::ReadResult read_x3d_xml_file(const std::string& path, vrml97::ReadOptions options) {
  options.source_name = path == "-" ? "<stdin>" : path;
  const FileBytes text(path);
  return read_x3d_xml(text.view(), options);
}

}  // namespace lodforge::x3dxml
