// What the X3D encodings know of a field: its value's shape (typed fields,
// the standard string and number fields, per-node exceptions), a node's
// default containerField and the classic default of a declared type.
#include "lodforge/io/vrml97/x3d_fields.h"

#include <gtest/gtest.h>

namespace lodforge::vrml97 {
namespace {

TEST(X3dFields, ShapesOfTypedTableAndPerNodeFields) {
  // Typed by the reader's table.
  EXPECT_EQ(x3d_value_shape("Transform", "translation"), ValueShape::kSFNumbers);
  EXPECT_EQ(x3d_value_shape("Transform", "children"), ValueShape::kNode);
  EXPECT_EQ(x3d_value_shape("IndexedFaceSet", "coordIndex"), ValueShape::kMFNumbers);
  EXPECT_EQ(x3d_value_shape("Viewpoint", "description"), ValueShape::kSFString);
  // The same name, another shape in another node.
  EXPECT_EQ(x3d_value_shape("NavigationInfo", "type"), ValueShape::kMFString);
  EXPECT_EQ(x3d_value_shape("ShaderPart", "type"), ValueShape::kSFString);
  EXPECT_EQ(x3d_value_shape("Extrusion", "scale"), ValueShape::kMFNumbers);
  EXPECT_EQ(x3d_value_shape("TextureTransform", "scale"), ValueShape::kSFNumbers);
  EXPECT_EQ(x3d_value_shape("Color", "color"), ValueShape::kMFNumbers);
  EXPECT_EQ(x3d_value_shape("Fog", "color"), ValueShape::kSFNumbers);
  EXPECT_EQ(x3d_value_shape("OrthoViewpoint", "fieldOfView"), ValueShape::kMFNumbers);
  EXPECT_EQ(x3d_value_shape("GeoViewpoint", "fieldOfView"), ValueShape::kUnknown);
  EXPECT_EQ(x3d_value_shape("Anchor", "parameter"), ValueShape::kMFString);
  EXPECT_EQ(x3d_value_shape("TextureCoordinateGenerator", "parameter"), ValueShape::kMFNumbers);
  // By name in any node, and unknown.
  EXPECT_EQ(x3d_value_shape("ImageTexture", "url"), ValueShape::kMFString);
  EXPECT_EQ(x3d_value_shape("PositionInterpolator", "keyValue"), ValueShape::kMFNumbers);
  EXPECT_EQ(x3d_value_shape("SomeExtension", "someField"), ValueShape::kUnknown);
}

TEST(X3dFields, DeclaredTypes) {
  EXPECT_EQ(shape_of_type("SFString"), ValueShape::kSFString);
  EXPECT_EQ(shape_of_type("MFString"), ValueShape::kMFString);
  EXPECT_EQ(shape_of_type("SFVec3f"), ValueShape::kSFNumbers);
  EXPECT_EQ(shape_of_type("MFRotation"), ValueShape::kMFNumbers);
  EXPECT_EQ(shape_of_type("MFNode"), ValueShape::kNode);
  EXPECT_EQ(shape_of_type("Vec3f"), ValueShape::kUnknown);
  EXPECT_EQ(default_classic_value("SFVec3f"), "0 0 0");
  EXPECT_EQ(default_classic_value("SFRotation"), "0 0 1 0");
  EXPECT_EQ(default_classic_value("SFBool"), "FALSE");
  EXPECT_EQ(default_classic_value("SFString"), "\"\"");
  EXPECT_EQ(default_classic_value("SFNode"), "NULL");
  EXPECT_EQ(default_classic_value("MFFloat"), "[]");
  EXPECT_EQ(default_classic_value("SFTime"), "0");
}

TEST(X3dFields, DefaultContainerFields) {
  EXPECT_EQ(default_container_field("IndexedFaceSet"), "geometry");
  EXPECT_EQ(default_container_field("Appearance"), "appearance");
  EXPECT_EQ(default_container_field("PhysicalMaterial"), "material");
  EXPECT_EQ(default_container_field("ImageTexture"), "texture");
  EXPECT_EQ(default_container_field("Coordinate"), "coord");
  EXPECT_EQ(default_container_field("TextureCoordinate"), "texCoord");
  EXPECT_EQ(default_container_field("ShaderPart"), "parts");
  EXPECT_EQ(default_container_field("CommonSurfaceShader"), "shaders");
  EXPECT_EQ(default_container_field("MetadataString"), "metadata");
  // Every other node, and a prefix of a listed name, fill `children`.
  EXPECT_EQ(default_container_field("Transform"), "children");
  EXPECT_EQ(default_container_field("Coord"), "children");
  EXPECT_EQ(default_container_field("Effect"), "children");  // as Castle Model Viewer has it
}

TEST(X3dFields, ClassicQuoting) {
  EXPECT_EQ(quote_classic("a \"b\" \\c"), "\"a \\\"b\\\" \\\\c\"");
  EXPECT_EQ(quote_classic(""), "\"\"");
}

}  // namespace
}  // namespace lodforge::vrml97
