#include "lodforge/io/x3dxml/write_x3d_xml.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/lexer.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/x3dxml/x3d_fields.h"

namespace lodforge::x3dxml {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// `v` as an XML attribute value with its quotes: single quotes when it holds
// double ones (MFString values), line breaks as character references so that
// attribute normalisation keeps them.
std::string attribute(std::string_view v) {
  const char q = v.find('"') != std::string_view::npos ? '\'' : '"';
  std::string out(1, q);
  for (char c : v) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += "&#9;";
        break;
      default:
        if (c == q)
          out += q == '"' ? "&quot;" : "&apos;";
        else
          out += c;
    }
  }
  out += q;
  return out;
}

// An MFString element: quoted, with '"' and '\' escaped.
std::string string_literal(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string typed_value(const FieldValue& v) {
  std::string out;
  auto sep = [&] {
    if (!out.empty()) out += ' ';
  };
  if (scene::float_components(v.type.kind) > 0) {
    for (float f : v.floats) {
      sep();
      out += fmt::format("{}", f);
    }
    return out;
  }
  if (v.type.kind == FieldKind::kBool) {
    for (int i : v.ints) {
      sep();
      out += i ? "true" : "false";
    }
    return out;
  }
  if (v.type.kind == FieldKind::kString) {
    if (!v.type.multi) return v.strings.empty() ? "" : v.strings.front();
    for (const auto& s : v.strings) {
      sep();
      out += string_literal(s);
    }
    return out;
  }
  for (int i : v.ints) {
    sep();
    out += fmt::format("{}", i);
  }
  return out;
}

// A value kept as classic text, restated for an attribute: comments and the
// outer brackets dropped, TRUE / FALSE lower case, a single string unquoted
// when the field is an SFString.
std::string raw_value(std::string_view raw, bool sf_string) {
  std::string out;
  for (std::size_t i = 0; i < raw.size();) {
    const char c = raw[i];
    if (c == '"') {
      std::size_t end = i + 1;
      while (end < raw.size() && raw[end] != '"') end += raw[end] == '\\' ? 2 : 1;
      end = std::min(end + 1, raw.size());
      out.append(raw.substr(i, end - i));
      i = end;
    } else if (c == '#') {
      while (i < raw.size() && raw[i] != '\n') ++i;
    } else if (std::isalpha(static_cast<unsigned char>(c))) {
      std::size_t end = i;
      while (end < raw.size() &&
             (std::isalnum(static_cast<unsigned char>(raw[end])) || raw[end] == '_' ||
              raw[end] == '.' || raw[end] == '-' || raw[end] == '+'))
        ++end;
      const std::string_view w = raw.substr(i, end - i);
      out += w == "TRUE" ? "true" : w == "FALSE" ? "false" : std::string(w);
      i = end;
    } else {
      out += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
      ++i;
    }
  }
  std::size_t b = out.find_first_not_of(' ');
  std::size_t e = out.find_last_not_of(' ');
  out = b == std::string::npos ? "" : out.substr(b, e - b + 1);
  if (out.size() >= 2 && out.front() == '[' && out.back() == ']') {
    out = out.substr(1, out.size() - 2);
    b = out.find_first_not_of(' ');
    e = out.find_last_not_of(' ');
    out = b == std::string::npos ? "" : out.substr(b, e - b + 1);
  }
  if (sf_string && out.size() >= 2 && out.front() == '"' && out.back() == '"')
    return vrml1::detail::unquote(out);
  return out;
}

std::string_view x3d_access(std::string_view a) {
  if (a == "field") return "initializeOnly";
  if (a == "exposedField") return "inputOutput";
  if (a == "eventIn") return "inputOnly";
  if (a == "eventOut") return "outputOnly";
  return a;
}

bool is_statement(std::string_view field) {
  return field == "ROUTE" || field == "IMPORT" || field == "EXPORT" || field == "PROTO" ||
         field == "EXTERNPROTO" || field == "PROFILE" || field == "COMPONENT" || field == "META" ||
         field == "UNIT";
}

// The program of a Script or shader node read from a CDATA section (a url of
// one string in the form the X3D XML reader gives it): written back as CDATA,
// after the declarations, where X3D XML keeps it.
std::optional<std::string> source_text(const scene::Field& url) {
  const std::string v = raw_value(url.raw, false);
  if (v.size() < 2 || v.front() != '"' || v.back() != '"') return std::nullopt;
  const std::string text = vrml1::detail::unquote(v);
  if (string_literal(text) != v || text.find("]]>") != std::string::npos) return std::nullopt;
  if (url.raw != "[  " + v + " ]") return std::nullopt;  // the form the reader gives
  return text;
}

class Writer {
 public:
  Writer(const scene::Scene& s) : scene_(s) {}

  std::string write() {
    if (!vrml97::is_vrml97_header(scene_.header))
      throw DataError(fmt::format("cannot write a scene with header '{}' as X3D XML",
                                  scene_.header.substr(0, 40)));
    vrml97_ = !vrml97::is_x3d_header(scene_.header);
    std::string version = "3.0";
    if (!vrml97_) {
      const std::string rest = scene_.header.substr(6);
      version = rest.substr(0, rest.find_first_of(" \t"));
    }
    count_uses();
    std::string profile;  // none if the scene names none (a VRML97 scene gets one on conversion)
    std::string head;
    for (const auto& r : scene_.roots) {
      if (!r->statement) continue;
      const std::vector<std::string> w = statement_words(r->raw_body);
      if (r->type == "PROFILE" && !w.empty()) profile = w[0];
      if (r->type == "COMPONENT" && !w.empty()) {
        std::string all;
        for (const auto& x : w) all += x;
        const auto colon = all.find(':');
        head += fmt::format("\t<component name={} level={} />\n", attribute(all.substr(0, colon)),
                            attribute(colon == std::string::npos ? "1" : all.substr(colon + 1)));
      }
      if (r->type == "UNIT" && w.size() >= 3)
        head += fmt::format("\t<unit category={} name={} conversionFactor={} />\n", attribute(w[0]),
                            attribute(w[1]), attribute(w[2]));
      if (r->type == "META" && w.size() >= 2)
        head += fmt::format("\t<meta name={} content={} />\n", attribute(w[0]), attribute(w[1]));
    }
    std::string body;
    for (const auto& r : scene_.roots) {
      if (r->statement)
        statement(r->type, r->raw_body, 1);
      else
        node(r, "", "", 1);
    }
    std::string out = fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<!DOCTYPE X3D PUBLIC \"ISO//Web3D//DTD X3D {0}//EN\" "
        "\"https://www.web3d.org/specifications/x3d-{0}.dtd\">\n"
        "<X3D{1} version={2}\n"
        "     xmlns:xsd=\"http://www.w3.org/2001/XMLSchema-instance\"\n"
        "     "
        "xsd:noNamespaceSchemaLocation=\"https://www.web3d.org/specifications/x3d-{0}.xsd\">\n",
        version, profile.empty() ? "" : " profile=" + attribute(profile), attribute(version));
    if (!head.empty()) out += "<head>\n" + head + "</head>\n";
    out += "<Scene>\n" + out_ + "</Scene>\n</X3D>\n";
    return out;
  }

 private:
  // The words and strings (unquoted) of a statement kept verbatim.
  static std::vector<std::string> statement_words(std::string_view raw) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < raw.size();) {
      if (std::isspace(static_cast<unsigned char>(raw[i]))) {
        ++i;
        continue;
      }
      std::size_t end = i + 1;
      if (raw[i] == '"') {
        while (end < raw.size() && raw[end] != '"') end += raw[end] == '\\' ? 2 : 1;
        end = std::min(end + 1, raw.size());
        out.push_back(vrml1::detail::unquote(raw.substr(i, end - i)));
      } else {
        while (end < raw.size() && !std::isspace(static_cast<unsigned char>(raw[end]))) ++end;
        out.emplace_back(raw.substr(i, end - i));
      }
      i = end;
    }
    return out;
  }

  // ROUTE, IMPORT and EXPORT as elements where they were; PROFILE,
  // COMPONENT, UNIT and META are in the header.
  void statement(std::string_view keyword, std::string_view raw, int depth) {
    if (keyword == "PROTO" || keyword == "EXTERNPROTO")
      throw DataError(fmt::format(
          "a {} cannot be written in the X3D XML encoding (its body is kept as classic text); "
          "write .x3dv",
          keyword));
    const std::vector<std::string> w = statement_words(raw);
    auto split = [](const std::string& s, std::string& a, std::string& b) {
      const auto dot = s.rfind('.');
      a = s.substr(0, dot);
      b = dot == std::string::npos ? "" : s.substr(dot + 1);
    };
    std::string a, b, c, d;
    if (keyword == "ROUTE" && w.size() >= 3) {  // from TO to
      split(w[0], a, b);
      split(w[2], c, d);
      indent(depth);
      out_ += fmt::format("<ROUTE fromNode={} fromField={} toNode={} toField={} />\n", attribute(a),
                          attribute(b), attribute(c), attribute(d));
    } else if (keyword == "IMPORT" && !w.empty()) {
      split(w[0], a, b);
      indent(depth);
      out_ += fmt::format("<IMPORT inlineDEF={} importedDEF={}{} />\n", attribute(a), attribute(b),
                          w.size() >= 3 ? " AS=" + attribute(w[2]) : "");
    } else if (keyword == "EXPORT" && !w.empty()) {
      indent(depth);
      out_ += fmt::format("<EXPORT localDEF={}{} />\n", attribute(w[0]),
                          w.size() >= 3 ? " AS=" + attribute(w[2]) : "");
    }
  }

  // Names for DEF / USE: a shared node without a name gets "lf_N", and a
  // shared node whose name another node also has gets "NAME_N" (a USE of it
  // could otherwise reach the other node), as the classic writer does.
  void count_uses() {
    std::unordered_map<std::string, int> names;
    std::vector<const Node*> order;
    std::vector<const Node*> stack;
    auto visit = [&](const NodePtr& n) {
      if (!n) return;
      if (uses_[n.get()]++ == 0) stack.push_back(n.get());
    };
    for (auto it = scene_.roots.rbegin(); it != scene_.roots.rend(); ++it) visit(*it);
    while (!stack.empty()) {
      const Node* n = stack.back();
      stack.pop_back();
      order.push_back(n);
      if (!n->name.empty()) ++names[n->name];
      for (const auto& f : n->fields)
        for (auto k = f.value.nodes.rbegin(); k != f.value.nodes.rend(); ++k) visit(*k);
    }
    std::unordered_map<std::string, int> next;
    for (const Node* n : order) {
      if (uses_[n] < 2 || (!n->name.empty() && names[n->name] < 2)) continue;
      const std::string base = n->name.empty() ? "lf" : n->name;
      std::string name;
      do name = fmt::format("{}_{}", base, ++next[base]);
      while (names.count(name));
      names[name] = 1;
      generated_[n] = name;
    }
  }

  std::string name_of(const Node* n) const {
    const auto it = generated_.find(n);
    return it != generated_.end() ? it->second : n->name;
  }

  void indent(int depth) { out_.append(static_cast<std::size_t>(depth), '\t'); }

  void node(const NodePtr& n, std::string_view parent, std::string_view field, int depth) {
    indent(depth);
    std::string container;
    if (!field.empty() && detail::default_container(n->type, parent) != field)
      container = " containerField=" + attribute(field);
    const std::string name = name_of(n.get());
    if (!written_.insert(n.get()).second) {
      out_ += fmt::format("<{} USE={}{} />\n", n->type, attribute(name), container);
      return;
    }
    out_ += "<" + n->type;
    if (!name.empty()) out_ += " DEF=" + attribute(name);
    out_ += container;
    // Attributes first, then the fields holding nodes as child elements.
    std::vector<const scene::Field*> elements;
    for (const auto& f : n->fields) {
      if (f.name.find(' ') != std::string::npos) {
        elements.push_back(&f);
        continue;
      }
      if (is_statement(f.name) || (!f.is_raw && f.value.type.kind == FieldKind::kNode)) {
        elements.push_back(&f);
        continue;
      }
      if (f.name == "url" && f.is_raw && source_text(f)) {
        elements.push_back(&f);  // the program as CDATA, after the declarations
        continue;
      }
      const std::string v = f.is_raw
                                ? raw_value(f.raw, detail::single_string_field(n->type, f.name))
                                : typed_value(f.value);
      out_ += fmt::format("\n");
      indent(depth + 1);
      out_ += f.name + "=" + attribute(v);
    }
    if (elements.empty()) {
      out_ += " />\n";
      return;
    }
    out_ += ">\n";
    for (const scene::Field* f : elements) {
      if (f->name.find(' ') != std::string::npos) {
        declaration(*f, n->type, depth + 1);
        continue;
      }
      if (is_statement(f->name)) {
        statement(f->name, f->raw, depth + 1);
        continue;
      }
      if (f->name == "url" && f->is_raw) {
        indent(depth + 1);
        out_ += "<![CDATA[" + *source_text(*f) + "]]>\n";
        continue;
      }
      std::string fname = f->name;
      if (vrml97_ && n->type == "LOD" && fname == "level") fname = "children";
      for (const auto& k : f->value.nodes) node(k, n->type, fname, depth + 1);
    }
    indent(depth);
    out_ += "</" + n->type + ">\n";
  }

  // `access TYPE name` with its value, as <field>.
  void declaration(const scene::Field& f, std::string_view parent, int depth) {
    const std::vector<std::string> w = statement_words(f.name);
    if (w.size() != 3) return;
    indent(depth);
    out_ += fmt::format("<field accessType={} type={} name={}", attribute(x3d_access(w[0])),
                        attribute(w[1]), attribute(w[2]));
    if (!f.is_raw && f.value.type.kind == FieldKind::kNode) {
      if (f.value.nodes.empty()) {
        out_ += " />\n";
        return;
      }
      out_ += ">\n";
      for (const auto& k : f.value.nodes) node(k, parent, "", depth + 1);
      indent(depth);
      out_ += "</field>\n";
      return;
    }
    if (!f.no_value) out_ += " value=" + attribute(raw_value(f.raw, w[1] == "SFString"));
    out_ += " />\n";
  }

  const scene::Scene& scene_;
  bool vrml97_ = false;
  std::unordered_map<const Node*, int> uses_;
  std::unordered_map<const Node*, std::string> generated_;
  std::unordered_set<const Node*> written_;
  std::string out_;
};

}  // namespace

std::string write_x3d_xml(const scene::Scene& scene) {
  return Writer(scene).write();
}

void write_x3d_xml_file(const scene::Scene& scene, const std::string& path) {
  write_file_atomic(path, write_x3d_xml(scene));
}

}  // namespace lodforge::x3dxml
