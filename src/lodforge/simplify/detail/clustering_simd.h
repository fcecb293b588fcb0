#pragma once
/// Four-float arithmetic for the scoring loops of vertex_clustering's
/// representative choice. Internal to simplify/.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace lodforge::detail::clustering {

/// sqrt(x) for x >= 0, without std::sqrt's errno path (a possible library
/// call on the hot path of a loop keeps its values in memory).
inline double sqrt_nonnegative(double x) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_setzero_pd(), _mm_set_sd(x)));
#else
  return std::sqrt(x);
#endif
}
inline float sqrt_nonnegative(float x) {
#if defined(__SSE2__)
  return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x)));
#else
  return std::sqrt(x);
#endif
}

/// Four floats, one per triangle or per candidate: the unit of the scoring
/// loops (SSE where the target has it; the library sqrt may set errno, which
/// keeps compilers from vectorising it in plain loops). A mask has all bits
/// of a lane set or none.
struct F4 {
#if defined(__SSE2__)
  __m128 v;
  static F4 load(const float* p) {
    return {_mm_loadu_ps(p)};
  }
  static F4 set(float a, float b, float c, float d) {
    return {_mm_setr_ps(a, b, c, d)};
  }
  /// The mask of the lanes whose integer equals `value`.
  static F4 lanes_equal(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                        std::uint32_t value) {
    const __m128i x = _mm_setr_epi32(int(a), int(b), int(c), int(d));
    return {_mm_castsi128_ps(_mm_cmpeq_epi32(x, _mm_set1_epi32(int(value))))};
  }
  /// The mask of the first n lanes.
  static F4 lanes_below(std::uint32_t n) {
    return {_mm_castsi128_ps(_mm_cmplt_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(int(n))))};
  }
  /// The lanes set in b but not in a.
  friend F4 and_not(F4 a, F4 b) {
    return {_mm_andnot_ps(a.v, b.v)};
  }
  /// a where the mask is set, else b.
  friend F4 select(F4 mask, F4 a, F4 b) {
    return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))};
  }
  /// a where the mask is set, else +0.
  friend F4 operator&(F4 a, F4 mask) {
    return {_mm_and_ps(a.v, mask.v)};
  }
  /// Rows to columns.
  friend void transpose(F4& a, F4& b, F4& c, F4& d) {
    _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v);
  }
  static F4 splat(float x) {
    return {_mm_set1_ps(x)};
  }
  void store(float* p) const {
    _mm_storeu_ps(p, v);
  }
  friend F4 operator+(F4 a, F4 b) {
    return {_mm_add_ps(a.v, b.v)};
  }
  friend F4 operator-(F4 a, F4 b) {
    return {_mm_sub_ps(a.v, b.v)};
  }
  friend F4 operator*(F4 a, F4 b) {
    return {_mm_mul_ps(a.v, b.v)};
  }
  friend F4 sqrt(F4 a) {
    return {_mm_sqrt_ps(a.v)};
  }
  friend F4 abs(F4 a) {
    return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)};
  }
#else
  std::array<float, 4> v;
  template <class Op>
  static F4 map(Op op) {
    F4 r;
    for (int l = 0; l < 4; ++l) r.v[l] = op(l);
    return r;
  }
  static F4 load(const float* p) {
    return map([&](int l) { return p[l]; });
  }
  static F4 set(float a, float b, float c, float d) {
    return {{a, b, c, d}};
  }
  static F4 lanes_equal(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                        std::uint32_t value) {
    const std::uint32_t x[4] = {a, b, c, d};
    return map([&](int l) { return std::bit_cast<float>(x[l] == value ? ~0u : 0u); });
  }
  static F4 lanes_below(std::uint32_t n) {
    return map([&](int l) { return std::bit_cast<float>(std::uint32_t(l) < n ? ~0u : 0u); });
  }
  friend F4 and_not(F4 a, F4 b) {
    return map([&](int l) {
      return std::bit_cast<float>(~std::bit_cast<std::uint32_t>(a.v[l]) &
                                  std::bit_cast<std::uint32_t>(b.v[l]));
    });
  }
  friend F4 select(F4 mask, F4 a, F4 b) {
    return map([&](int l) { return std::bit_cast<std::uint32_t>(mask.v[l]) ? a.v[l] : b.v[l]; });
  }
  friend F4 operator&(F4 a, F4 mask) {
    return map([&](int l) { return std::bit_cast<std::uint32_t>(mask.v[l]) ? a.v[l] : 0.0f; });
  }
  friend void transpose(F4& a, F4& b, F4& c, F4& d) {
    const F4 r[4] = {a, b, c, d};
    F4* out[4] = {&a, &b, &c, &d};
    for (int i = 0; i < 4; ++i) *out[i] = map([&](int l) { return r[l].v[i]; });
  }
  static F4 splat(float x) {
    return map([&](int) { return x; });
  }
  void store(float* p) const {
    std::copy(v.begin(), v.end(), p);
  }
  friend F4 operator+(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] + b.v[l]; });
  }
  friend F4 operator-(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] - b.v[l]; });
  }
  friend F4 operator*(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] * b.v[l]; });
  }
  friend F4 sqrt(F4 a) {
    return map([&](int l) { return std::sqrt(a.v[l]); });
  }
  friend F4 abs(F4 a) {
    return map([&](int l) { return std::abs(a.v[l]); });
  }
#endif
};
constexpr std::size_t kLanes = 4;

}  // namespace lodforge::detail::clustering
