// tessera/math.h — small vector and matrix types for scenes and cameras.
//
// Conventions: right-handed world space, column vectors, matrices stored column-major
// (m[column][row]) like OpenGL/glTF. `perspective` maps view-space depth to OpenGL clip space
// (z in [-w, w] after projection, camera looking down -z). The vector functions keep GLSL's
// names (`dot`, `cross`, `length`, `normalize`): the CPU kernels mirror the shaders.
// Tests: tests/unit/scene_test.cpp (cameras and transforms), raster_test.cpp.
#pragma once

#include <cmath>

namespace tessera {

struct Vec2 {
  float x = 0, y = 0;
};

struct Vec3 {
  float x = 0, y = 0, z = 0;
  Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  float operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};

inline float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& a) { return std::sqrt(dot(a, a)); }
/// Unit vector in the direction of `a`; the zero vector stays zero.
inline Vec3 normalize(const Vec3& a) {
  const float l = length(a);
  return l > 0 ? a * (1.0f / l) : a;
}

struct Vec4 {
  float x = 0, y = 0, z = 0, w = 0;
};

/// 4x4 matrix, column-major: m[c][r].
struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  static Mat4 identity() { return {}; }
  Mat4 operator*(const Mat4& o) const {
    Mat4 r;
    for (int c = 0; c < 4; ++c) {
      for (int row = 0; row < 4; ++row) {
        float s = 0;
        for (int k = 0; k < 4; ++k) s += m[k][row] * o.m[c][k];
        r.m[c][row] = s;
      }
    }
    return r;
  }
  Vec4 operator*(const Vec4& v) const {
    return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z + m[3][0] * v.w,
            m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z + m[3][1] * v.w,
            m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z + m[3][2] * v.w,
            m[0][3] * v.x + m[1][3] * v.y + m[2][3] * v.z + m[3][3] * v.w};
  }
  /// Transforms a point (w = 1), dropping w.
  Vec3 transform_point(const Vec3& p) const {
    const Vec4 r = (*this) * Vec4{p.x, p.y, p.z, 1.0f};
    return {r.x, r.y, r.z};
  }
  /// Transforms a direction (w = 0).
  Vec3 transform_vector(const Vec3& v) const {
    const Vec4 r = (*this) * Vec4{v.x, v.y, v.z, 0.0f};
    return {r.x, r.y, r.z};
  }
};

/// Inverse of an affine or general invertible matrix (cofactor expansion). A singular matrix
/// returns the identity.
Mat4 inverse(const Mat4& a);
/// Transpose.
Mat4 transpose(const Mat4& a);
/// Translation, scale, and rotation by a unit quaternion (x, y, z, w) as in glTF.
Mat4 translation(const Vec3& t);
Mat4 scaling(const Vec3& s);
Mat4 rotation_quat(float qx, float qy, float qz, float qw);
/// View matrix looking from `eye` at `target` with `up` (gluLookAt).
Mat4 look_at(const Vec3& eye, const Vec3& target, const Vec3& up);
/// OpenGL perspective projection (gluPerspective): vertical field of view in degrees,
/// aspect = width / height, near and far > 0.
Mat4 perspective(float fov_y_degrees, float aspect, float near_z, float far_z);

}  // namespace tessera
