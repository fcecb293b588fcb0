// Mat4: the transforms of a scene graph and what they do to points,
// vectors and normals.
#include "lodforge/core/math.h"

#include <gtest/gtest.h>

#include "core/expect_near.h"

#include <cmath>

namespace lodforge {
namespace {

constexpr float kHalfPi = 1.57079632679f;

using test::expect_near;

TEST(Mat4, TranslationScaleAndRotationMovePointsAndVectors) {
  const Mat4 t = Mat4::translation({1, 2, 3});
  EXPECT_EQ(t.transform_point({1, 1, 1}), (Vec3{2, 3, 4}));
  EXPECT_EQ(t.transform_vector({1, 1, 1}), (Vec3{1, 1, 1}));  // vectors ignore translation
  EXPECT_EQ(Mat4::scale({2, 3, 4}).transform_point({1, 1, 1}), (Vec3{2, 3, 4}));
  // A quarter turn about z (axis need not be unit) takes x to y.
  expect_near(Mat4::rotation({0, 0, 5}, kHalfPi).transform_point({1, 0, 0}), {0, 1, 0});
  expect_near(Mat4::rotation({1, 0, 0}, kHalfPi).transform_point({0, 1, 0}), {0, 0, 1});
  EXPECT_EQ(Mat4::rotation({0, 0, 0}, 1.f), Mat4{});  // zero axis: identity
}

TEST(Mat4, ProductAppliesTheRightFactorFirst) {
  const Mat4 m = Mat4::translation({1, 0, 0}) * Mat4::scale({2, 2, 2});
  EXPECT_EQ(m.transform_point({1, 1, 1}), (Vec3{3, 2, 2}));
  const Mat4 n = Mat4::scale({2, 2, 2}) * Mat4::translation({1, 0, 0});
  EXPECT_EQ(n.transform_point({1, 1, 1}), (Vec3{4, 2, 2}));
}

TEST(Mat4, FromVrmlReadsRowVectorsAndProjectiveRowsDivide) {
  // VRML's SFMatrix: the translation is in the last row.
  const float v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
  EXPECT_EQ(Mat4::from_vrml(v), Mat4::translation({5, 6, 7}));
  const float w[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2};
  EXPECT_EQ(Mat4::from_vrml(w).transform_point({2, 4, 6}), (Vec3{1, 2, 3}));
}

TEST(Mat4, NormalMatrixKeepsNormalsPerpendicularUnderNonUniformScale) {
  const Mat4 m = Mat4::scale({4, 1, 1}) * Mat4::rotation({0, 0, 1}, 0.5f);
  // A surface through the origin with tangent u and normal n.
  const Vec3 u = normalized(Vec3{1, 1, 0}), n = normalized(Vec3{1, -1, 0});
  const Vec3 nu = m.transform_vector(u), nn = m.normal_matrix().transform_vector(n);
  EXPECT_NEAR(dot(nu, nn), 0.f, 1e-5f);
  EXPECT_GT(dot(nn, m.transform_vector(n)), 0.f);  // same side
  // A mirror keeps the normal on the side it was on.
  const Mat4 mirror = Mat4::scale({-1, 1, 1});
  EXPECT_EQ(mirror.normal_matrix().transform_vector({1, 0, 0}), (Vec3{-1, 0, 0}));
  EXPECT_EQ(Mat4::scale({1, 0, 1}).normal_matrix(), Mat4{});  // singular: identity
}

TEST(Mat4, MaxScaleIsTheLongestImageOfAUnitAxis) {
  EXPECT_FLOAT_EQ(Mat4{}.max_scale(), 1.f);
  EXPECT_NEAR((Mat4::rotation({1, 2, 3}, 0.7f) * Mat4::scale({2, -5, 3})).max_scale(), 5.f, 1e-5f);
  EXPECT_FLOAT_EQ(Mat4::translation({100, 0, 0}).max_scale(), 1.f);
}

}  // namespace
}  // namespace lodforge
