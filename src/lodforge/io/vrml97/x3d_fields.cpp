#include "lodforge/io/vrml97/x3d_fields.h"

#include <algorithm>
#include <iterator>

#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge::vrml97 {
namespace {

template <std::size_t N>
bool listed(const std::string_view (&list)[N], std::string_view name) {
  return std::find(std::begin(list), std::end(list), name) != std::end(list);
}

// Fields of one node type whose shape differs from the general rule below.
struct NodeField {
  std::string_view node;
  std::string_view field;
  ValueShape shape;
};
constexpr NodeField kNodeFields[] = {
    {"NavigationInfo", "type", ValueShape::kMFString},
    {"MultiTexture", "mode", ValueShape::kMFString},
    {"MultiTexture", "source", ValueShape::kMFString},
    {"MultiTexture", "function", ValueShape::kMFString},
    {"MetadataString", "value", ValueShape::kMFString},
    {"Extrusion", "scale", ValueShape::kMFNumbers},
    {"OrthoViewpoint", "fieldOfView", ValueShape::kMFNumbers},
    {"TextureCoordinateGenerator", "parameter", ValueShape::kMFNumbers},
    {"Extrusion", "orientation", ValueShape::kMFNumbers},
    {"Color", "color", ValueShape::kMFNumbers},
    {"ColorRGBA", "color", ValueShape::kMFNumbers},
};

constexpr std::string_view kMFStringFields[] = {
    "url",     "string",    "info",       "parameter",      "family",
    "justify", "geoSystem", "objectType", "transitionType", "frontUrl",
    "backUrl", "leftUrl",   "rightUrl",   "topUrl",         "bottomUrl",
};

constexpr std::string_view kSFStringFields[] = {
    "description",
    "title",
    "style",
    "language",
    "fogType",
    "reference",
    "boundaryModeS",
    "boundaryModeT",
    "boundaryModeR",
    "magnificationFilter",
    "minificationFilter",
    "textureCompression",
    "alphaMode",
    "version",
    "name",
    "type",
    "mode",
    "update",
    "compareMode",
    "shading",
    "sortKey",
    "forceTransitions",
};

// Single values of several numbers in the standard nodes.
constexpr std::string_view kSFNumberFields[] = {
    "translation",
    "rotation",
    "scale",
    "scaleOrientation",
    "center",
    "bboxCenter",
    "bboxSize",
    "size",
    "position",
    "orientation",
    "centerOfRotation",
    "direction",
    "location",
    "attenuation",
    "diffuseColor",
    "specularColor",
    "emissiveColor",
    "baseColor",
    "color",
    "axisOfRotation",
    "offset",
    "maxPosition",
    "minPosition",
    "axisRotation",
    "upVector",
    "image",
    "hatchColor",
    "borderColor",
    "up",
    "gravityUp",
    "skyColorRGB",
    "groundColorRGB",
    "mediumColor",
    "backgroundColor",
};

// Lists of numbers in the standard nodes (and Castle Game Engine's).
constexpr std::string_view kMFNumberFields[] = {
    "key",
    "keyValue",
    "keyVelocity",
    "range",
    "height",
    "coordIndex",
    "colorIndex",
    "normalIndex",
    "texCoordIndex",
    "index",
    "point",
    "vector",
    "skyColor",
    "groundColor",
    "skyAngle",
    "groundAngle",
    "crossSection",
    "spine",
    "stripCount",
    "fanCount",
    "vertexCount",
    "avatarSize",
    "weight",
    "knot",
    "uKnot",
    "vKnot",
    "skinCoordIndex",
    "skinCoordWeight",
    "value",
    "lineSegments",
    "dimensions",
    "inverseBindMatrices",
    "keyValueQuaternions",
    "depthMap",
    "length",
    "jointBindingPositions",
    "jointBindingRotations",
    "jointBindingScales",
    "llimit",
    "ulimit",
};

struct Container {
  std::string_view field;
  std::string_view types;  // space-separated node types
};
constexpr Container kContainers[] = {
    {"geometry",
     " Box Cone Cylinder Sphere IndexedFaceSet IndexedLineSet IndexedTriangleSet "
     "IndexedTriangleFanSet IndexedTriangleStripSet IndexedQuadSet TriangleSet TriangleFanSet "
     "TriangleStripSet QuadSet LineSet PointSet ElevationGrid Extrusion Text Arc2D ArcClose2D "
     "Circle2D Disk2D Polyline2D Polypoint2D Rectangle2D TriangleSet2D NurbsPatchSurface "
     "NurbsCurve NurbsTrimmedSurface NurbsSweptSurface NurbsSwungSurface GeoElevationGrid "
     "Teapot "},
    {"appearance", " Appearance "},
    {"material", " Material TwoSidedMaterial PhysicalMaterial UnlitMaterial "},
    {"texture",
     " ImageTexture PixelTexture MovieTexture MultiTexture ComposedTexture3D ImageTexture3D "
     "PixelTexture3D ComposedCubeMapTexture GeneratedCubeMapTexture ImageCubeMapTexture "
     "RenderedTexture ShaderTexture GeneratedShadowMap "},
    {"textureTransform",
     " TextureTransform MultiTextureTransform TextureTransform3D TextureTransformMatrix3D "},
    {"coord", " Coordinate CoordinateDouble GeoCoordinate "},
    {"normal", " Normal "},
    {"color", " Color ColorRGBA "},
    {"texCoord",
     " TextureCoordinate TextureCoordinate3D TextureCoordinate4D MultiTextureCoordinate "
     "TextureCoordinateGenerator NurbsTextureCoordinate "},
    {"tangent", " Tangent "},
    {"source", " AudioClip "},
    {"geoOrigin", " GeoOrigin "},
    {"trimmingContour", " Contour2D "},
    {"emitter",
     " ConeEmitter ExplosionEmitter PointEmitter PolylineEmitter SurfaceEmitter VolumeEmitter "},
    {"physics", " BoundedPhysicsModel ForcePhysicsModel WindPhysicsModel "},
    {"bodies", " RigidBody "},
    {"layers", " Layer LayoutLayer "},
    {"viewport", " Viewport "},
    {"layout", " Layout "},
    {"fontStyle", " FontStyle ScreenFontStyle "},
    {"shaders", " ComposedShader PackagedShader ProgramShader CommonSurfaceShader "},
    {"parts", " ShaderPart EffectPart "},
    {"programs", " ShaderProgram "},
    {"metadata",
     " MetadataBoolean MetadataDouble MetadataFloat MetadataInteger MetadataSet MetadataString "},
    {"textureProperties", " TextureProperties "},
    {"fillProperties", " FillProperties "},
    {"lineProperties", " LineProperties "},
    {"attrib", " FloatVertexAttribute Matrix3VertexAttribute Matrix4VertexAttribute "},
    {"fogCoord", " FogCoordinate "},
};

}  // namespace

ValueShape shape_of_type(std::string_view type_name) {
  if (type_name.size() < 3 || (type_name[0] != 'S' && type_name[0] != 'M') ||
      type_name.substr(1, 1) != "F")
    return ValueShape::kUnknown;
  const bool multi = type_name[0] == 'M';
  const std::string_view base = type_name.substr(2);
  if (base == "Node") return ValueShape::kNode;
  if (base == "String") return multi ? ValueShape::kMFString : ValueShape::kSFString;
  return multi ? ValueShape::kMFNumbers : ValueShape::kSFNumbers;
}

ValueShape x3d_value_shape(std::string_view node_type, std::string_view field) {
  for (const auto& nf : kNodeFields)
    if (nf.node == node_type && nf.field == field) return nf.shape;
  scene::FieldType typed;
  if (typed_field(node_type, field, typed)) {
    if (typed.kind == scene::FieldKind::kNode) return ValueShape::kNode;
    if (typed.kind == scene::FieldKind::kString)
      return typed.multi ? ValueShape::kMFString : ValueShape::kSFString;
    return typed.multi ? ValueShape::kMFNumbers : ValueShape::kSFNumbers;
  }
  if (listed(kMFStringFields, field)) return ValueShape::kMFString;
  if (listed(kSFStringFields, field)) return ValueShape::kSFString;
  if (listed(kSFNumberFields, field)) return ValueShape::kSFNumbers;
  if (listed(kMFNumberFields, field)) return ValueShape::kMFNumbers;
  return ValueShape::kUnknown;
}

std::string_view default_container_field(std::string_view node_type) {
  std::string key = " ";
  key.append(node_type);
  key += ' ';
  for (const auto& c : kContainers)
    if (c.types.find(key) != std::string_view::npos) return c.field;
  return "children";
}

std::string default_classic_value(std::string_view type_name) {
  if (type_name.starts_with("MF")) return "[]";
  static constexpr std::pair<std::string_view, std::string_view> kDefaults[] = {
      {"SFBool", "FALSE"},
      {"SFString", "\"\""},
      {"SFNode", "NULL"},
      {"SFVec2f", "0 0"},
      {"SFVec2d", "0 0"},
      {"SFVec3f", "0 0 0"},
      {"SFVec3d", "0 0 0"},
      {"SFColor", "0 0 0"},
      {"SFVec4f", "0 0 0 0"},
      {"SFVec4d", "0 0 0 0"},
      {"SFColorRGBA", "0 0 0 0"},
      {"SFRotation", "0 0 1 0"},
      {"SFImage", "0 0 0"},
      {"SFMatrix3f", "1 0 0 0 1 0 0 0 1"},
      {"SFMatrix3d", "1 0 0 0 1 0 0 0 1"},
      {"SFMatrix4f", "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"},
      {"SFMatrix4d", "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"},
  };
  for (const auto& [t, v] : kDefaults)
    if (t == type_name) return std::string(v);
  return "0";  // SFFloat, SFDouble, SFInt32, SFTime
}

bool is_number_token(std::string_view t) {
  const char c = t.empty() ? ' ' : t[0];
  if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') return true;
  // What the classic reader's number parser takes too (an overflowing
  // number is read as, and written back as, inf).
  return t == "inf" || t == "nan" || t == "infinity";
}

bool is_bool_token(std::string_view t) {
  return t == "true" || t == "false" || t == "TRUE" || t == "FALSE";
}

std::string quote_classic(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace lodforge::vrml97
