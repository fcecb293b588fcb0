// coin_probe FILE [LOD_CHILD]: reads one Inventor / VRML 1.0 file with
// Coin3D, the independent reader the conformance tests use as an oracle, and
// prints one JSON object on stdout (with LOD_CHILD, every LOD and
// LevelOfDetail node draws its child LOD_CHILD, or its last, for the
// traversal's counts: Coin would choose by a view volume the probe has not):
//
//   ok               Coin read the file (SoDB::readAll would return a root)
//   error            Coin's read errors (SoReadError), one per line; some,
//                    such as a texture file that cannot be read, are posted
//                    for files Coin accepts
//   warnings         Coin's other messages (SoDebugError), one per line
//   node_counts      distinct node instances per VRML type name
//   ifs_triangles    triangles SoCallbackAction generates for IndexedFaceSets
//   primitive_counts shape instances met by the traversal, per type (a USEd
//                    shape counts every time, Switch follows whichChild)
//   shape_triangles  triangles generated per shape type by the traversal
//   distinct_triangles  the same, counting only triangles whose three corners
//                    are at three different points (degenerate ones aside)
//
// The first line of the output is {"read":true|false}, printed before the
// traversal; the JSON object above is the second.
//
// Coin aborts or crashes on some broken inputs (a USE inside its own DEF, a
// missing materialIndex), so callers run this program as a child process with
// a timeout and treat a crash as "Coin rejected the file".
//
// Why not SoDB::readAll itself: readAll wraps the top-level nodes in its own
// SoSeparator and removes the wrapper again when the file holds a single
// top-level Separator, so afterwards the wrapper cannot be told from a
// Separator of the file. The loop below is readAll's loop (SoDB::read until
// the input is exhausted, then any trailing characters are an error Coin
// reports but tolerates) and keeps the top-level nodes apart.
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPath.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/VRMLnodes/SoVRMLLOD.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/actions/SoSearchAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/lists/SoPathList.h>
#include <Inventor/misc/SoChildList.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoLOD.h>
#include <Inventor/nodes/SoLevelOfDetail.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoSwitch.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace {

/// SoInput with readAll's end-of-input test made reachable.
class ProbeInput : public SoInput {
 public:
  using SoInput::skipWhiteSpace;
};

/// SoBase::getFileFormatName is protected; a member pointer taken through a
/// derived class reaches it (the class is never instantiated).
struct FileFormatName : SoBase {
  static const char* of(const SoBase* base) {
    return (base->*(&FileFormatName::getFileFormatName))();
  }
};

void collect_message(const SoError* error, void* data) {
  auto* messages = static_cast<std::string*>(data);
  if (!messages->empty()) messages->push_back('\n');
  messages->append(error->getDebugString().getString());
}

/// The name a node has in a VRML 1.0 file: Coin's class name without "So",
/// or the file's name for nodes Coin does not know.
std::string vrml_type_name(const SoNode* node) {
  // SoUnknownNode's header is not installed; its type is registered by name.
  static const SoType kUnknownNode = SoType::fromName("SoUnknownNode");
  if (node->isOfType(kUnknownNode)) return FileFormatName::of(node);
  std::string name = node->getTypeId().getName().getString();
  if (name.rfind("So", 0) == 0) name.erase(0, 2);
  return name;
}

void count_nodes(SoNode* node, std::set<const SoNode*>& seen,
                 std::map<std::string, std::size_t>& counts) {
  // Iterative: files may nest deeply, the probe must not overflow its stack.
  std::vector<SoNode*> stack{node};
  while (!stack.empty()) {
    SoNode* n = stack.back();
    stack.pop_back();
    if (n == nullptr || !seen.insert(n).second) continue;
    ++counts[vrml_type_name(n)];
    if (SoChildList* children = n->getChildren()) {
      for (int i = children->getLength() - 1; i >= 0; --i) stack.push_back((*children)[i]);
    }
  }
}

struct TraversalCounts {
  std::map<std::string, std::size_t> shapes;
  std::map<std::string, std::size_t> triangles;
  std::map<std::string, std::size_t> distinct;
  std::string current;
};

SoCallbackAction::Response on_shape(void* data, SoCallbackAction*, const SoNode* node) {
  auto* counts = static_cast<TraversalCounts*>(data);
  counts->current = vrml_type_name(node);
  ++counts->shapes[counts->current];
  return SoCallbackAction::CONTINUE;
}

void on_triangle(void* data, SoCallbackAction*, const SoPrimitiveVertex* a,
                 const SoPrimitiveVertex* b, const SoPrimitiveVertex* c) {
  auto* counts = static_cast<TraversalCounts*>(data);
  ++counts->triangles[counts->current];
  const SbVec3f& p = a->getPoint();
  const SbVec3f& q = b->getPoint();
  const SbVec3f& r = c->getPoint();
  if (p != q && q != r && r != p) ++counts->distinct[counts->current];
}

// Every LOD / LevelOfDetail / VRML97 LOD under `root` becomes a Switch on child `k` (or
// its last) with the same children.
void fix_lod_children(SoNode* root, int k) {
  for (SoType type :
       {SoLOD::getClassTypeId(), SoLevelOfDetail::getClassTypeId(), SoVRMLLOD::getClassTypeId()}) {
    SoSearchAction search;
    search.setType(type);
    search.setInterest(SoSearchAction::ALL);
    search.setSearchingAll(TRUE);
    search.apply(root);
    std::set<SoNode*> done;
    const SoPathList& paths = search.getPaths();
    for (int i = 0; i < paths.getLength(); ++i) {
      SoPath* path = paths[i];
      auto* lod = static_cast<SoGroup*>(path->getTail());
      if (path->getLength() < 2 || !done.insert(lod).second) continue;
      auto* parent = static_cast<SoGroup*>(path->getNodeFromTail(1));
      auto* chosen = new SoSwitch;
      for (int c = 0; c < lod->getNumChildren(); ++c) chosen->addChild(lod->getChild(c));
      chosen->whichChild = lod->getNumChildren() == 0 ? -1 : std::min(k, lod->getNumChildren() - 1);
      for (int c = 0; c < parent->getNumChildren(); ++c)
        if (parent->getChild(c) == lod) parent->replaceChild(c, chosen);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: coin_probe FILE [LOD_CHILD]\n");
    return 2;
  }
  const int lod_child = argc == 3 ? std::atoi(argv[2]) : -1;
  SoDB::init();
  std::string errors;
  std::string warnings;
  SoReadError::setHandlerCallback(collect_message, &errors);
  SoDebugError::setHandlerCallback(collect_message, &warnings);

  nlohmann::json out;
  out["ok"] = false;
  ProbeInput input;
  std::vector<SoNode*> roots;
  bool ok = false;
  if (input.openFile(argv[1])) {
    if (!input.isValidFile()) {
      SoReadError::post(&input, "Not a valid Inventor file.");
    } else {
      ok = true;
      SoNode* node = nullptr;
      do {
        if (!SoDB::read(&input, node)) {
          ok = false;
          break;
        }
        if (node != nullptr) {
          node->ref();
          roots.push_back(node);
        }
      } while (node != nullptr && input.skipWhiteSpace());
      if (ok && !input.eof()) {
        SoReadError::post(&input, "Erroneous character(s) after end of scene graph");
      }
    }
  }
  out["ok"] = ok;
  // The verdict on reading first, on a line of its own: Coin crashes in some
  // traversals (an indexed binding without its index field), and the caller
  // still learns that Coin read the file.
  std::printf("{\"read\":%s}\n", ok ? "true" : "false");
  std::fflush(stdout);

  std::set<const SoNode*> seen;
  std::map<std::string, std::size_t> node_counts;
  TraversalCounts traversal;
  if (ok) {
    auto* root = new SoSeparator;
    root->ref();
    for (SoNode* node : roots) {
      count_nodes(node, seen, node_counts);
      root->addChild(node);
    }
    if (lod_child >= 0) fix_lod_children(root, lod_child);
    SoCallbackAction action;
    action.addPreCallback(SoShape::getClassTypeId(), on_shape, &traversal);
    action.addTriangleCallback(SoShape::getClassTypeId(), on_triangle, &traversal);
    action.apply(root);
    root->unref();
  }
  for (SoNode* node : roots) node->unref();

  out["error"] = errors;
  out["warnings"] = warnings;
  out["node_counts"] = node_counts;
  out["ifs_triangles"] = traversal.triangles.count("IndexedFaceSet") != 0
                             ? traversal.triangles["IndexedFaceSet"]
                             : std::size_t{0};
  out["primitive_counts"] = traversal.shapes;
  out["shape_triangles"] = traversal.triangles;
  out["distinct_triangles"] = traversal.distinct;
  std::puts(out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  return 0;
}
