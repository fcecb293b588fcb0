// Joining VRML nodes, after the original thesis §4.1.5 (Figure "Joining"):
//  1. remove unnecessary Separators (Separator { Separator { ... } });
//  2. in every group, find runs of consecutive joinable Separators and merge
//     each run into one Separator { [Material] [MaterialBinding PER_FACE_INDEXED]
//     Coordinate3 [Normal] [TextureCoordinate2] IndexedFaceSet }.
//
//  | a Separator is joinable when it                          |
//  |----------------------------------------------------------|
//  | has no DEF name, and nothing in it is shared or named     |
//  | holds exactly one IndexedFaceSet with <= max_faces faces,  |
//  |   possibly nested in Separators/Groups, and its own        |
//  |   Coordinate3 before it                                    |
//  | holds Info nodes (they move into the joined Separator)     |
//  | holds otherwise only a one-row Material (binding OVERALL/ |
//  |   DEFAULT or absent), Normal (binding per vertex indexed  |
//  |   or DEFAULT or absent), TextureCoordinate2, ShapeHints   |
//  |   (the same in every piece of the run)                    |
//  | Pieces of one run agree on having a Material, normals and texture coordinates. |
#include "lodforge/lod/join_nodes.h"

#include <fmt/format.h>

#include <array>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/scene/schema.h"

namespace lodforge {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

constexpr std::array<const char*, 6> kMaterialFields = {
    "ambientColor", "diffuseColor", "specularColor", "emissiveColor", "shininess", "transparency"};

struct Piece {
  const Node* material = nullptr;
  const Node* coords = nullptr;
  const Node* normal = nullptr;
  const Node* texcoords = nullptr;
  const Node* faces = nullptr;
  const Node* hints = nullptr;
  std::vector<NodePtr> infos;  ///< Info nodes of the piece, kept in the joined one
};

class Joiner {
 public:
  Joiner(const JoinOptions& o, Log& log) : opt_(o), log_(log) {}

  JoinStatistics run(scene::Scene& s) {
    for (const auto& r : s.roots) count(r);
    for (auto& r : s.roots) visit(r);
    return stats_;
  }

 private:
  void count(const NodePtr& n) {
    if (++refs_[n.get()] > 1) return;
    for (const auto& c : n->children) count(c);
  }

  bool private_node(const Node* n) const {
    auto it = refs_.find(n);
    return n->name.empty() && it != refs_.end() && it->second == 1;
  }

  void visit(NodePtr& n) {
    if (visited_.count(n.get())) return;
    visited_.insert(n.get());
    for (auto& c : n->children) visit(c);
    // Separator { Separator { ... } }: the outer one adds nothing.
    for (auto& c : n->children) {
      while (c->type == "Separator" && private_node(c.get()) && c->fields.empty() &&
             c->children.size() == 1 && c->children[0]->type == "Separator" &&
             private_node(c->children[0].get())) {
        NodePtr inner = c->children[0];
        c = inner;
        ++stats_.separators_removed;
      }
    }
    if (!n->is_raw && !n->children.empty() && n->type != "Switch" && n->type != "LOD")
      join_runs(*n);
  }

  // Walks a candidate piece with a local traversal state: group nodes
  // (Separator scoping kept), the attribute nodes listed above, Info nodes
  // (carried over), and exactly one IndexedFaceSet, which must come after its
  // Coordinate3 inside the piece.
  bool walk(const Node& n, Piece& state, Piece& p, bool& found) const {
    for (const auto& cp : n.children) {
      const Node* c = cp.get();
      if (!private_node(c) || c->is_raw) return false;
      const std::string& t = c->type;
      if (t == "Separator" || t == "Group") {
        if (!c->fields.empty()) return false;
        Piece inner = state;
        if (!walk(*c, t == "Separator" ? inner : state, p, found)) return false;
        continue;
      }
      if (!c->children.empty()) return false;
      if (t == "Info") {
        p.infos.push_back(cp);
      } else if (t == "Material") {
        // One material per piece (its faces all take it).
        for (const char* f : kMaterialFields)
          if (const FieldValue* v = c->value(f); v && v->count() > 1) return false;
        state.material = c;
      } else if (t == "Coordinate3") {
        state.coords = c;
      } else if (t == "Normal") {
        state.normal = c;
      } else if (t == "TextureCoordinate2") {
        state.texcoords = c;
      } else if (t == "ShapeHints") {
        state.hints = c;
      } else if (t == "MaterialBinding" || t == "NormalBinding") {
        // Bindings that mean the same in the joined set are allowed.
        const FieldValue* v = scene::field_or_default(*c, "value");
        const std::string b = v->strings.empty() ? "" : v->strings[0];
        bool same = t == "MaterialBinding" ? (b == "OVERALL" || b == "DEFAULT")
                                           : (b == "PER_VERTEX_INDEXED" || b == "DEFAULT");
        if (!same) return false;
      } else if (t == "IndexedFaceSet") {
        // (An Inventor vertexProperty brings coordinates of its own.)
        if (found || !state.coords || !scene::field_nodes(*c).empty()) return false;
        found = true;
        const Node* faces = c;
        p.material = state.material;
        p.coords = state.coords;
        p.normal = state.normal;
        p.texcoords = state.texcoords;
        p.hints = state.hints;
        p.faces = faces;
      } else {
        return false;
      }
    }
    return true;
  }

  bool piece_of(const Node& sep, Piece& p) const {
    if (sep.type != "Separator" || !private_node(&sep) || !sep.fields.empty()) return false;
    Piece state;
    bool found = false;
    if (!walk(sep, state, p, found) || !found) return false;
    const FieldValue* ci = scene::field_or_default(*p.faces, "coordIndex");
    std::size_t faces = 0;
    for (std::int32_t i : ci->ints) faces += i < 0;
    if (ci->ints.empty() || faces > opt_.max_faces) return false;
    if (p.faces->value("materialIndex")) return false;
    if (!p.normal && p.faces->value("normalIndex")) return false;
    if (!p.texcoords && p.faces->value("textureCoordIndex")) return false;
    return true;
  }

  static bool compatible(const Piece& a, const Piece& b) {
    bool same_hints =
        (!a.hints && !b.hints) || (a.hints && b.hints && a.hints->fields == b.hints->fields);
    return same_hints && (a.material != nullptr) == (b.material != nullptr) &&
           (a.normal != nullptr) == (b.normal != nullptr) &&
           (a.texcoords != nullptr) == (b.texcoords != nullptr);
  }

  void join_runs(Node& group) {
    std::vector<NodePtr> out;
    std::size_t i = 0;
    auto& kids = group.children;
    while (i < kids.size()) {
      Piece first;
      if (!piece_of(*kids[i], first)) {
        out.push_back(kids[i++]);
        continue;
      }
      std::vector<Piece> run = {first};
      std::size_t j = i + 1;
      for (; j < kids.size(); ++j) {
        Piece p;
        if (!piece_of(*kids[j], p) || !compatible(first, p)) break;
        run.push_back(p);
      }
      if (run.size() < 2) {
        out.push_back(kids[i++]);
        continue;
      }
      out.push_back(merge(run, kids[i]->first_line));
      ++stats_.runs;
      stats_.joined += run.size() - 1;
      i = j;
    }
    kids = std::move(out);
  }

  // Appends a field's values (or its default) as `rows` rows.
  static void append_material(std::vector<std::vector<float>>& fields, const Node& m) {
    std::size_t rows = 1;
    for (const char* f : kMaterialFields)
      if (const FieldValue* v = m.value(f)) rows = std::max(rows, v->count());
    for (std::size_t k = 0; k < kMaterialFields.size(); ++k) {
      const FieldValue* v = scene::field_or_default(m, kMaterialFields[k]);
      std::size_t comps = std::size_t(scene::float_components(v->type.kind));
      std::size_t count = v->floats.size() / comps;
      for (std::size_t r = 0; r < rows; ++r) {
        std::size_t src = count == 0 ? 0 : std::min(r, count - 1);
        for (std::size_t c = 0; c < comps; ++c)
          fields[k].push_back(count == 0 ? 0.f : v->floats[src * comps + c]);
      }
    }
  }

  NodePtr merge(const std::vector<Piece>& run, int line) {
    auto sep = std::make_shared<Node>();
    sep->type = "Separator";
    sep->first_line = line;
    std::vector<float> points, normals, texs;
    std::vector<std::int32_t> coord_index, normal_index, tex_index, material_index;
    std::vector<std::vector<float>> material(kMaterialFields.size());
    std::size_t faces_total = 0;
    for (const Piece& p : run) {
      auto base = std::int32_t(points.size() / 3);
      auto nbase = std::int32_t(normals.size() / 3);
      auto tbase = std::int32_t(texs.size() / 2);
      auto mat = std::int32_t(material[1].size() / 3);
      const auto& pts = scene::field_or_default(*p.coords, "point")->floats;
      points.insert(points.end(), pts.begin(), pts.end());
      if (p.normal) {
        const auto& v = scene::field_or_default(*p.normal, "vector")->floats;
        normals.insert(normals.end(), v.begin(), v.end());
      }
      if (p.texcoords) {
        const auto& v = scene::field_or_default(*p.texcoords, "point")->floats;
        texs.insert(texs.end(), v.begin(), v.end());
      }
      if (p.material) append_material(material, *p.material);
      const auto& ci = scene::field_or_default(*p.faces, "coordIndex")->ints;
      const FieldValue* ni = p.faces->value("normalIndex");
      const FieldValue* ti = p.faces->value("textureCoordIndex");
      bool default_ni = !ni || (ni->ints.size() == 1 && ni->ints[0] == -1);
      bool default_ti = !ti || (ti->ints.size() == 1 && ti->ints[0] == -1);
      bool open = false;
      for (std::size_t k = 0; k < ci.size(); ++k) {
        std::int32_t c = ci[k];
        auto shifted = [&](std::int32_t v, std::int32_t b) { return v < 0 ? -1 : v + b; };
        coord_index.push_back(shifted(c, base));
        if (p.normal) {
          std::int32_t n = default_ni ? c : (k < ni->ints.size() ? ni->ints[k] : -1);
          normal_index.push_back(shifted(n, nbase));
        }
        if (p.texcoords) {
          std::int32_t t = default_ti ? c : (k < ti->ints.size() ? ti->ints[k] : -1);
          tex_index.push_back(shifted(t, tbase));
        }
        open = c >= 0;
        if (c < 0) {
          ++faces_total;
          if (p.material) material_index.push_back(mat);
        }
      }
      if (open) {  // a last face without its -1
        coord_index.push_back(-1);
        if (p.normal) normal_index.push_back(-1);
        if (p.texcoords) tex_index.push_back(-1);
        ++faces_total;
        if (p.material) material_index.push_back(mat);
      }
    }
    if (run.front().material) {
      auto m = std::make_shared<Node>();
      m->type = "Material";
      for (std::size_t k = 0; k < kMaterialFields.size(); ++k) {
        FieldKind kind = k < 4 ? FieldKind::kColor : FieldKind::kFloat;
        m->set(kMaterialFields[k], scene::make_floats(kind, true, material[k]));
      }
      sep->children.push_back(m);
      auto b = std::make_shared<Node>();
      b->type = "MaterialBinding";
      b->set("value", scene::make_enum("PER_FACE_INDEXED"));
      sep->children.push_back(b);
    }
    for (const Piece& p : run)
      for (const auto& info : p.infos) sep->children.push_back(info);
    if (run.front().hints) sep->children.push_back(std::make_shared<Node>(*run.front().hints));
    auto coords = std::make_shared<Node>();
    coords->type = "Coordinate3";
    coords->set("point", scene::make_floats(FieldKind::kVec3f, true, std::move(points)));
    sep->children.push_back(coords);
    if (run.front().normal) {
      auto n = std::make_shared<Node>();
      n->type = "Normal";
      n->set("vector", scene::make_floats(FieldKind::kVec3f, true, std::move(normals)));
      sep->children.push_back(n);
      auto b = std::make_shared<Node>();
      b->type = "NormalBinding";
      b->set("value", scene::make_enum("PER_VERTEX_INDEXED"));
      sep->children.push_back(b);
    }
    if (run.front().texcoords) {
      auto t = std::make_shared<Node>();
      t->type = "TextureCoordinate2";
      t->set("point", scene::make_floats(FieldKind::kVec2f, true, std::move(texs)));
      sep->children.push_back(t);
    }
    auto ifs = std::make_shared<Node>();
    ifs->type = "IndexedFaceSet";
    ifs->first_line = line;
    ifs->set("coordIndex", scene::make_longs(std::move(coord_index)));
    if (!material_index.empty())
      ifs->set("materialIndex", scene::make_longs(std::move(material_index)));
    if (!normal_index.empty()) ifs->set("normalIndex", scene::make_longs(std::move(normal_index)));
    if (!tex_index.empty()) ifs->set("textureCoordIndex", scene::make_longs(std::move(tex_index)));
    sep->children.push_back(ifs);
    log_.info(LogCategory::kJoin, fmt::format("line {}: joined {} IndexedFaceSets ({} faces)", line,
                                              run.size(), faces_total));
    return sep;
  }

  const JoinOptions& opt_;
  Log& log_;
  JoinStatistics stats_;
  std::unordered_map<const Node*, std::size_t> refs_;
  std::unordered_set<const Node*> visited_;
};

}  // namespace

JoinStatistics join_nodes(scene::Scene& scene, const JoinOptions& options, Log& log) {
  return Joiner(options, log).run(scene);
}

}  // namespace lodforge
