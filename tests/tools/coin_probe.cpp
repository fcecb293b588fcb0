// coin_probe FILE: reads one Inventor / VRML 1.0 file with Coin3D, the
// independent reader the conformance tests use as an oracle, and prints one
// JSON object on stdout:
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
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/misc/SoChildList.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>

#include <cstdio>
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
  std::string current;
};

SoCallbackAction::Response on_shape(void* data, SoCallbackAction*, const SoNode* node) {
  auto* counts = static_cast<TraversalCounts*>(data);
  counts->current = vrml_type_name(node);
  ++counts->shapes[counts->current];
  return SoCallbackAction::CONTINUE;
}

void on_triangle(void* data, SoCallbackAction*, const SoPrimitiveVertex*, const SoPrimitiveVertex*,
                 const SoPrimitiveVertex*) {
  auto* counts = static_cast<TraversalCounts*>(data);
  ++counts->triangles[counts->current];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: coin_probe FILE\n");
    return 2;
  }
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
  std::puts(out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  return 0;
}
