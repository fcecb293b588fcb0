#include "lodforge/io/x3dxml/x3d_fields.h"

#include <algorithm>

namespace lodforge::x3dxml::detail {
namespace {

bool in_list(std::string_view word, std::string_view list) {
  std::size_t pos = 0;
  while (pos < list.size()) {
    std::size_t end = list.find(' ', pos);
    if (end == std::string_view::npos) end = list.size();
    if (list.substr(pos, end - pos) == word) return true;
    pos = end + 1;
  }
  return false;
}

bool ends_with(std::string_view s, std::string_view e) {
  return s.size() >= e.size() && s.substr(s.size() - e.size()) == e;
}

constexpr std::string_view kGeometry =
    "Arc2D ArcClose2D Box Circle2D Cone Cylinder Disk2D ElevationGrid Extrusion GeoElevationGrid "
    "IndexedFaceSet IndexedLineSet IndexedQuadSet IndexedTriangleFanSet IndexedTriangleSet "
    "IndexedTriangleStripSet LineSet NurbsCurve NurbsPatchSurface NurbsSweptSurface "
    "NurbsSwungSurface NurbsTrimmedSurface PointSet Polyline2D Polypoint2D QuadSet Rectangle2D "
    "Sphere Teapot Text TriangleFanSet TriangleSet TriangleSet2D TriangleStripSet";

// Child types whose default field does not depend on the parent.
struct Default {
  std::string_view field;
  std::string_view types;
};
constexpr Default kDefaults[] = {
    {"appearance", "Appearance"},
    {"material", "Material TwoSidedMaterial PhysicalMaterial UnlitMaterial"},
    {"textureTransform",
     "TextureTransform MultiTextureTransform TextureTransform3D TextureTransformMatrix3D"},
    {"coord", "Coordinate CoordinateDouble GeoCoordinate"},
    {"normal", "Normal"},
    {"color", "Color ColorRGBA"},
    {"texCoord",
     "TextureCoordinate TextureCoordinate3D TextureCoordinate4D MultiTextureCoordinate "
     "TextureCoordinateGenerator"},
    {"fontStyle", "FontStyle ScreenFontStyle"},
    {"fogCoord", "FogCoordinate"},
    {"parts", "ShaderPart"},
    {"programs", "ShaderProgram"},
    {"shaders", "ComposedShader PackagedShader ProgramShader CommonSurfaceShader"},
    {"attrib", "FloatVertexAttribute Matrix3VertexAttribute Matrix4VertexAttribute"},
    {"textureProperties", "TextureProperties"},
    {"effects", "Effect"},
    {"parts", "EffectPart"},
};

}  // namespace

std::string_view default_container(std::string_view child, std::string_view parent) {
  if (in_list(child, kGeometry)) return "geometry";
  if (child.starts_with("Metadata")) return parent == "MetadataSet" ? "value" : "metadata";
  if (child == "field") return "field";
  if (ends_with(child, "Texture") || ends_with(child, "Texture3D") ||
      ends_with(child, "CubeMapTexture") || child == "MultiTexture")
    return "texture";
  for (const auto& d : kDefaults)
    if (in_list(child, d.types)) return d.field;
  return "children";
}

bool single_node_field(std::string_view parent, std::string_view field) {
  // A list field keeps its brackets; any other node field (appearance,
  // normalMap, Castle's and X3D 4's texture slots, ...) holds one node.
  if (field == "texture") return parent != "MultiTexture" && parent != "ComposedTexture3D";
  return !in_list(field,
                  "children level choice shaders programs parts attrib value layers viewports "
                  "joints segments sites skin skinCoord displacers effects watchList "
                  "trimmingContour");
}

bool single_vector_field(std::string_view parent, std::string_view field) {
  if (field == "color")  // a light's or MultiTexture's colour; Color / ColorRGBA hold lists
    return parent != "Color" && parent != "ColorRGBA";
  if (field == "size") return parent != "Text";
  return in_list(field,
                 "translation rotation scale scaleOrientation center bboxCenter bboxSize "
                 "position orientation direction location diffuseColor emissiveColor "
                 "specularColor baseColor attenuation axisOfRotation centerOfRotation upVector "
                 "image hitPoint_changed plane axis axis1 axis2 anchorPoint offset maxPosition "
                 "minPosition ambientFactor diffuseFactor emissiveFactor specularFactor "
                 "reflectionFactor transmissionFactor up projectionCenter matrix focusCenter");
}

bool single_string_field(std::string_view parent, std::string_view field) {
  if (field == "type")
    return parent == "ShaderPart" || parent == "ShaderProgram" || parent == "EffectPart";
  if (field == "language") return true;
  if (field == "style") return parent == "FontStyle" || parent == "ScreenFontStyle";
  return in_list(field,
                 "description name reference title appinfo documentation fogType alphaMode "
                 "shadowMapFormat");
}

}  // namespace lodforge::x3dxml::detail
