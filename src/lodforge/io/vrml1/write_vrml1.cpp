// VRML 1.0 writer. Numbers are written in their shortest round-trip form
// (fmt's Dragonbox), so reading the output gives the same floats bit for bit.
// DEF/USE: a node met a second time is written as USE; names are kept, shared
// nodes without a name get one, and a name that a later USE could not reach
// (rebound in between) is made unique.
#include "lodforge/io/vrml1/write_vrml1.h"

#include <fmt/compile.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <functional>
#include <iterator>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/file_io.h"

namespace lodforge::vrml1 {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// Numbers are formatted into a local buffer and appended: formatting
// through a back_inserter of the output string costs several times more.
void append_number(std::string& out, std::int32_t i) {
  const fmt::format_int text(i);
  out.append(text.data(), text.size());
}
void append_float(std::string& out, float f) {
  char buffer[32];
  out.append(buffer, fmt::format_to_n(buffer, sizeof buffer, FMT_COMPILE("{}"), f).out);
}
void append_hex(std::string& out, std::int32_t i) {
  fmt::format_to(std::back_inserter(out), "{:#x}", static_cast<std::uint32_t>(i));
}
void append_string(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

class Writer {
 public:
  /// Appends to `out`; with a `drain`, hands it the text whenever it holds
  /// more than kDrainBytes (a node's start), so a big scene is never whole
  /// in memory as text.
  Writer(const WriteOptions& options, std::string& out,
         std::function<void(std::string&)> drain = {})
      : opt_(options), out_(out), drain_(std::move(drain)) {}

  void write(const scene::Scene& s) {
    for (const auto& r : s.roots) count_refs(r);
    for (const auto& [node, refs] : refs_)
      if (!node->name.empty()) used_names_.insert(node->name);
    out_ += s.header.empty() ? "#VRML V1.0 ascii" : s.header;
    out_ += "\n\n";
    for (const auto& r : s.roots) {
      write_node(r, 0);
      out_ += '\n';
    }
  }

 private:
  void count_refs(const NodePtr& n) {
    if (++refs_[n.get()] > 1) return;
    for (const auto& f : n->fields)
      for (const auto& c : f.value.nodes)
        if (c) count_refs(c);
    for (const auto& c : n->children) count_refs(c);
  }

  void newline(int depth) { newline(out_, depth); }
  void newline(std::string& out, int depth) const {
    if (opt_.minimize) {
      out += ' ';
      return;
    }
    out += '\n';
    if (!opt_.no_tabs) out.append(static_cast<std::size_t>(depth), '\t');
  }

  std::string unique_name(const std::string& base) {
    for (int i = 1;; ++i) {
      std::string n = fmt::format("{}_{}", base.empty() ? "lf" : base, i);
      if (used_names_.insert(n).second) return n;
    }
  }

  void write_node(const NodePtr& n, int depth) {
    if (drain_ && out_.size() > kDrainBytes) drain_(out_);
    auto written = names_.find(n.get());
    if (written != names_.end()) {
      out_ += "USE ";
      out_ += written->second;
      --pending_[n.get()];
      return;
    }
    std::size_t refs = refs_[n.get()];
    std::string name = n->name;
    if (refs > 1) {
      // A later USE must reach this node: the name must not be bound to
      // another node that is still to be USEd.
      auto bound = bound_.find(name);
      if (name.empty() ||
          (bound != bound_.end() && bound->second != n.get() && pending_[bound->second] > 0))
        name = unique_name(name);
      names_[n.get()] = name;
      pending_[n.get()] = refs - 1;
    }
    if (!name.empty()) {
      out_ += "DEF ";
      out_ += name;
      out_ += ' ';
      bound_[name] = n.get();
    }
    out_ += n->type;
    if (n->statement) {
      out_ += ' ';
      out_ += n->raw_body;
      return;
    }
    out_ += " {";
    if (n->is_raw) {
      out_ += n->raw_body;
      out_ += '}';
      return;
    }
    if (n->has_declaration) {
      newline(depth + 1);
      out_ += "fields [";
      for (std::size_t i = 0; i < n->declared.size(); ++i) {
        out_ += i ? ", " : " ";
        out_ += scene::type_name(n->declared[i].type);
        out_ += ' ';
        out_ += n->declared[i].name;
      }
      out_ += " ]";
      if (!n->is_a.empty()) {
        newline(depth + 1);
        out_ += "isA [";
        for (std::size_t i = 0; i < n->is_a.size(); ++i) {
          out_ += i ? ", " : " ";
          append_string(out_, n->is_a[i]);
        }
        out_ += " ]";
      }
    }
    for (const auto& f : n->fields) {
      newline(depth + 1);
      out_ += f.name;
      if (!f.no_value) {
        out_ += ' ';
        if (f.is_raw)
          out_ += f.raw;
        else
          write_value(f.value, depth + 1);
      }
      // Open Inventor's marks: the ignore flag and a connection, as read.
      if (f.ignored) out_ += " ~";
      if (!f.connection.empty()) {
        out_ += " = ";
        out_ += f.connection;
      }
    }
    for (const auto& c : n->children) {
      newline(depth + 1);
      write_node(c, depth + 1);
    }
    newline(depth);
    out_ += '}';
  }

  // Values of one kind, `per_value` numbers each, wrapped after `per_line`.
  // A long list is formatted in pieces on all cores and appended in order
  // (the text is the same: where a value's separator and line break go
  // depends only on its place in the list).
  template <typename T, typename Emit>
  void write_list(const std::vector<T>& v, std::size_t per_value, int per_line, int depth,
                  Emit emit) {
    std::size_t count = per_value ? v.size() / per_value : 0;
    if (count == 1) {
      for (std::size_t k = 0; k < per_value; ++k) {
        if (k) out_ += ' ';
        emit(out_, v[k]);
      }
      return;
    }
    const ListLayout layout{.per_value = per_value,
                            .per_line = std::max<std::size_t>(
                                1, static_cast<std::size_t>(std::max(per_line, 1)) / per_value),
                            .depth = depth};
    out_ += '[';
    if (count * per_value < kParallelNumbers) {
      write_values(out_, v, layout, 0, count, emit);
    } else {
      const std::size_t pieces = (count + kPieceValues - 1) / kPieceValues;
      std::vector<std::string> text(pieces);
      tbb::parallel_for(std::size_t(0), pieces, [&](std::size_t p) {
        // Formatted into a local string: the pieces' string headers are
        // neighbours in `text`, and appending there would share cache lines.
        std::string piece;
        write_values(piece, v, layout, p * kPieceValues, std::min(count, (p + 1) * kPieceValues),
                     emit);
        text[p] = std::move(piece);
      });
      for (const auto& t : text) out_ += t;
    }
    if (!opt_.minimize && count > 0) newline(out_, depth);
    out_ += ']';
  }

  struct ListLayout {
    std::size_t per_value;  // numbers per value
    std::size_t per_line;   // values per line
    int depth;
  };

  // Values [first, last) of a list, each after its separator.
  template <typename T, typename Emit>
  void write_values(std::string& out, const std::vector<T>& v, const ListLayout& layout,
                    std::size_t first, std::size_t last, Emit emit) const {
    for (std::size_t i = first; i < last; ++i) {
      if (i) out += ',';
      if (!opt_.minimize && i % layout.per_line == 0)
        newline(out, layout.depth + 1);
      else if (i || !opt_.minimize)
        out += ' ';
      for (std::size_t k = 0; k < layout.per_value; ++k) {
        if (k) out += ' ';
        emit(out, v[i * layout.per_value + k]);
      }
    }
  }

  void write_value(const FieldValue& v, int depth) {
    auto emit_float = [](std::string& out, float f) { append_float(out, f); };
    auto emit_int = [](std::string& out, std::int32_t i) { append_number(out, i); };
    switch (v.type.kind) {
      case FieldKind::kColor:
      case FieldKind::kFloat:
      case FieldKind::kMatrix:
      case FieldKind::kRotation:
      case FieldKind::kVec2f:
      case FieldKind::kVec3f: {
        std::size_t per = static_cast<std::size_t>(scene::float_components(v.type.kind));
        if (v.type.multi)
          write_list(v.floats, per, opt_.floats_per_line, depth, emit_float);
        else
          write_list(v.floats, v.floats.size(), opt_.floats_per_line, depth, emit_float);
        return;
      }
      case FieldKind::kNode: {
        // SFNode: the node or NULL; MFNode: a list of nodes.
        if (!v.type.multi) {
          if (v.nodes.empty() || !v.nodes[0])
            out_ += "NULL";
          else
            write_node(v.nodes[0], depth);
          return;
        }
        out_ += '[';
        for (std::size_t i = 0; i < v.nodes.size(); ++i) {
          if (i) out_ += ',';
          newline(depth + 1);
          if (v.nodes[i])
            write_node(v.nodes[i], depth + 1);
          else
            out_ += "NULL";
        }
        if (!v.nodes.empty()) newline(depth);
        out_ += ']';
        return;
      }
      case FieldKind::kUInt32: {
        auto emit_hex = [](std::string& out, std::int32_t i) { append_hex(out, i); };
        if (v.type.multi)
          write_list(v.ints, 1, opt_.ints_per_line, depth, emit_hex);
        else
          write_list(v.ints, v.ints.size(), opt_.ints_per_line, depth, emit_hex);
        return;
      }
      case FieldKind::kLong:
        if (v.type.multi)
          write_list(v.ints, 1, opt_.ints_per_line, depth, emit_int);
        else
          write_list(v.ints, v.ints.size(), opt_.ints_per_line, depth, emit_int);
        return;
      case FieldKind::kBool: {
        auto emit_bool = [](std::string& out, std::int32_t b) { out += b ? "TRUE" : "FALSE"; };
        write_list(v.ints, 1, opt_.ints_per_line, depth, emit_bool);
        return;
      }
      case FieldKind::kString: {
        auto emit = [](std::string& out, const std::string& s) { append_string(out, s); };
        write_list(v.strings, 1, 1, depth, emit);
        return;
      }
      case FieldKind::kEnum: {
        auto emit = [](std::string& out, const std::string& s) { out += s; };
        write_list(v.strings, 1, opt_.ints_per_line, depth, emit);
        return;
      }
      case FieldKind::kBitMask:
        if (v.strings.size() == 1) {
          out_ += v.strings[0];
        } else {
          out_ += '(';
          for (std::size_t i = 0; i < v.strings.size(); ++i) {
            out_ += i ? " | " : " ";
            out_ += v.strings[i];
          }
          out_ += " )";
        }
        return;
      case FieldKind::kImage: {
        // width height components, then the pixels as hexadecimal numbers.
        for (std::size_t i = 0; i < v.ints.size(); ++i) {
          if (i >= 3 && opt_.ints_per_line > 0 && (i - 3) % std::size_t(opt_.ints_per_line) == 0 &&
              !opt_.minimize)
            newline(depth + 1);
          else if (i)
            out_ += ' ';
          if (i < 3)
            append_number(out_, v.ints[i]);
          else
            append_hex(out_, v.ints[i]);
        }
        return;
      }
    }
  }

  const WriteOptions& opt_;
  std::string& out_;
  static constexpr std::size_t kDrainBytes = std::size_t{1} << 20;
  static constexpr std::size_t kParallelNumbers = std::size_t{1} << 15;  // a list this long
  static constexpr std::size_t kPieceValues = std::size_t{1} << 13;      // values per piece
  std::function<void(std::string&)> drain_;
  std::unordered_map<const Node*, std::size_t> refs_;
  std::unordered_map<const Node*, std::string> names_;    // shared nodes already written
  std::unordered_map<const Node*, std::size_t> pending_;  // USEs still to write
  std::unordered_map<std::string, const Node*> bound_;    // what each name means now
  std::unordered_set<std::string> used_names_;
};

}  // namespace

std::string write_vrml1(const scene::Scene& scene, const WriteOptions& options) {
  std::string out;
  Writer(options, out).write(scene);
  return out;
}

void write_vrml1_file(const scene::Scene& scene, const std::string& path,
                      const WriteOptions& options) {
  AtomicFileWriter file(path);
  std::string text;
  Writer(options, text, [&](std::string& t) {
    file.write(t);
    t.clear();
  }).write(scene);
  file.write(text);
  file.commit();
}

}  // namespace lodforge::vrml1
