// tessera/scene.h — triangle scenes from OBJ and glTF 2.0 files, cameras and orbits.
//
// A `Scene` is flattened for rendering: every mesh primitive becomes a `Mesh` whose vertices are
// already in world space (node transforms applied, normals transformed by the inverse
// transpose), with one material each. Textures are decoded 8-bit sRGB images owned by the
// scene. Loaders validate indices and sizes and report malformed files as one-line errors
// naming the file; they never trust a count in a file before checking it against the data.
//
// Supported: OBJ (triangulated polygons, positions, normals, UVs, MTL `Kd` and `map_Kd`) via
// tinyobjloader; glTF 2.0 (.gltf with external or data-URI buffers, and .glb) via tinygltf:
// the default scene's node hierarchy with TRS or matrix transforms, triangle primitives with
// POSITION / NORMAL / TEXCOORD_0, indexed or not, base-colour factor and texture, alpha mode,
// double-sidedness, and KHR_lights_punctual point lights. Skins and animations are ignored
// (meshes render in their bind pose). Missing normals are computed (area-weighted), missing UVs
// are zero.
// Tests: tests/unit/scene_test.cpp (OBJ, glTF, cameras, bad files).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/math.h"

namespace tessera::scene {

/// Surface description (unlit base colour plus what shading models need).
struct Material {
  std::string name;
  float base_color[4] = {1, 1, 1, 1};  ///< Linear RGBA factor (glTF's name: baseColorFactor).
  int base_color_texture = -1;         ///< Index into Scene::textures, -1 for none (glTF's
                                       ///< baseColorTexture).
  int normal_texture = -1;             ///< Index into Scene::textures, -1 for none.
  bool double_sided = true;
  bool alpha_mask = false;  ///< glTF alphaMode MASK.
  float alpha_cutoff = 0.5f;
  bool alpha_blend = false;  ///< glTF alphaMode BLEND (rendered as opaque by tessera).
};

/// Triangles with one material, vertices in world space.
struct Mesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;           ///< Same count as positions, unit length.
  std::vector<Vec2> uvs;               ///< Same count as positions.
  std::vector<std::uint32_t> indices;  ///< 3 per triangle, each < positions.size().
  int material = 0;                    ///< Index into Scene::materials.

  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// A punctual point light (KHR_lights_punctual), world space.
struct PointLight {
  Vec3 position;
  float color[3] = {1, 1, 1};  ///< Linear RGB (KHR_lights_punctual's name, kept).
  float intensity = 1.0f;
  float range = 0.0f;  ///< 0 = infinite.
};

/// A texture image with its sampling colour space.
struct Texture {
  std::string name;
  ImageRGBA8 image;
  bool srgb = true;  ///< Base colour is sRGB; normal maps are linear.
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;  ///< Never empty after loading (a default is added).
  std::vector<Texture> textures;
  std::vector<PointLight> lights;
  Vec3 bounds_min, bounds_max;  ///< Axis-aligned bounds of all vertices.

  std::size_t triangle_count() const;
  /// Recomputes bounds_min/bounds_max from the meshes.
  void update_bounds();
};

/// Limits applied while loading (a malicious file cannot ask for more).
struct LoadOptions {
  std::size_t max_triangles = 1u << 26;
  bool load_textures = true;
};

/// Reads a Wavefront OBJ (+ MTL and its textures) / a glTF 2.0 (.gltf or .glb) scene; errors
/// name the file.
Result<Scene> load_obj(const std::string& path, const LoadOptions& options = {});
Result<Scene> load_gltf(const std::string& path, const LoadOptions& options = {});
/// By extension: .obj, .gltf, .glb.
Result<Scene> load_scene(const std::string& path, const LoadOptions& options = {});

/// A built-in procedural scene: a textured ground plane, boxes and a sphere with sharp
/// silhouettes, thin geometry and high-frequency textures (the anti-aliasing stress cases),
/// plus a few point lights. Deterministic.
Scene builtin_scene();

/// Perspective camera.
struct Camera {
  Vec3 eye{0, 0, 5};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  float fov_y_degrees = 60.0f;
  float near_z = 0.05f;
  float far_z = 1000.0f;

  Mat4 view() const { return look_at(eye, target, up); }
  Mat4 projection(float aspect) const { return perspective(fov_y_degrees, aspect, near_z, far_z); }
  Mat4 view_projection(float aspect) const { return projection(aspect) * view(); }
};

/// Parses "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov" (10 numbers). Fails with invalid_argument.
Result<Camera> parse_camera(const std::string& text);

/// Camera on a circular orbit around the scene's bounds: frame `frame` of `frames` (0-based) at
/// angle 2 pi frame / frames, radius 0.9 x the bounds' half-diagonal (horizontally), height
/// centre.y + 0.3 x half-diagonal, looking at the centre, 60 degree field of view; near and far
/// fitted to the bounds.
Camera orbit_camera(const Scene& scene, int frame, int frames);

/// Camera from command-line text: `camera` ("ex,ey,ez,tx,ty,tz,ux,uy,uz,fov") when non-empty,
/// else `orbit` ("FRAME/N") when non-empty, else the orbit's frame 0; near and far are always
/// fitted to the scene's bounds. Fails with invalid_argument on malformed text.
Result<Camera> camera_from_text(const Scene& scene, const std::string& camera,
                                const std::string& orbit);

}  // namespace tessera::scene
