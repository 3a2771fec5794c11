// Wavefront OBJ (+ MTL) loading through tinyobjloader.
#include <tiny_obj_loader.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <tuple>
#include <unordered_map>

#include "scene_internal.h"

namespace tessera::scene {

namespace {

struct CornerKey {
  int v, n, t;
  bool operator==(const CornerKey& o) const { return v == o.v && n == o.n && t == o.t; }
};
struct CornerHash {
  std::size_t operator()(const CornerKey& k) const {
    return std::size_t(k.v) * 73856093u ^ std::size_t(k.n) * 19349663u ^
           std::size_t(k.t) * 83492791u;
  }
};

}  // namespace

Result<Scene> load_obj(const std::string& path, const LoadOptions& options) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = detail::folder_of(path);
  tinyobj::ObjReader reader;
  if (std::FILE* probe = std::fopen(path.c_str(), "rb")) {
    std::fclose(probe);
  } else {
    return Status::error(ErrorCode::io_error, path + ": cannot open: " + std::strerror(errno));
  }
  if (!reader.ParseFromFile(path, config)) {
    return scene::detail::obj_parse_error(path, reader.Error());
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const auto& shapes = reader.GetShapes();
  const auto& mtls = reader.GetMaterials();

  Scene scene;
  // Materials: MTL diffuse colour (sRGB in the file, linearised) and map_Kd.
  std::map<std::string, int> texture_index;
  for (const tinyobj::material_t& m : mtls) {
    Material mat;
    mat.name = m.name;
    for (int c = 0; c < 3; ++c) mat.base_color[c] = srgb_to_linear(float(m.diffuse[c]));
    mat.base_color[3] = float(m.dissolve);
    if (!m.diffuse_texname.empty() && options.load_textures) {
      auto it = texture_index.find(m.diffuse_texname);
      if (it == texture_index.end()) {
        Result<ImageRGBA8> img =
            detail::load_texture_image(path, config.mtl_search_path + m.diffuse_texname);
        if (!img) return img.status();
        it = texture_index.emplace(m.diffuse_texname, int(scene.textures.size())).first;
        scene.textures.push_back({m.diffuse_texname, std::move(*img), true});
      }
      mat.base_color_texture = it->second;
    }
    scene.materials.push_back(std::move(mat));
  }
  const int default_material = int(scene.materials.size());
  scene.materials.push_back(Material{"default"});

  const std::size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
                    nt = attrib.texcoords.size() / 2;
  std::size_t triangles = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    // One mesh per (shape, material).
    std::map<int, Mesh> by_material;
    std::map<int, std::unordered_map<CornerKey, std::uint32_t, CornerHash>> corners;
    const auto& idx = shape.mesh.indices;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const int fv = shape.mesh.num_face_vertices[f];
      if (fv != 3 || offset + 3 > idx.size()) {
        return Status::error(ErrorCode::corrupt_data, path + ": face " + std::to_string(f) +
                                                          " of '" + shape.name +
                                                          "' could not be triangulated");
      }
      if (++triangles > options.max_triangles) {
        return Status::error(
            ErrorCode::too_large,
            path + ": more than " + std::to_string(options.max_triangles) + " triangles");
      }
      int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      if (mat < 0 || mat >= default_material) mat = default_material;
      Mesh& mesh = by_material[mat];
      auto& map = corners[mat];
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& i = idx[offset + std::size_t(k)];
        if (i.vertex_index < 0 || std::size_t(i.vertex_index) >= nv ||
            (i.normal_index >= 0 && std::size_t(i.normal_index) >= nn) ||
            (i.texcoord_index >= 0 && std::size_t(i.texcoord_index) >= nt)) {
          return Status::error(ErrorCode::corrupt_data,
                               path + ": face " + std::to_string(f) + " of '" + shape.name +
                                   "' refers to a missing vertex, normal or texture coordinate");
        }
        const CornerKey key{i.vertex_index, i.normal_index, i.texcoord_index};
        auto [it, inserted] = map.emplace(key, std::uint32_t(mesh.positions.size()));
        if (inserted) {
          const std::size_t v = std::size_t(i.vertex_index);
          mesh.positions.push_back(
              {attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]});
          if (i.normal_index >= 0) {
            const std::size_t n = std::size_t(i.normal_index);
            mesh.normals.push_back(
                {attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]});
          }
          if (i.texcoord_index >= 0) {
            const std::size_t t = std::size_t(i.texcoord_index);
            // OBJ's v axis points up; tessera's texture rows go down.
            mesh.uvs.push_back({attrib.texcoords[2 * t], 1.0f - attrib.texcoords[2 * t + 1]});
          }
        }
        mesh.indices.push_back(it->second);
      }
      offset += 3;
    }
    for (auto& [mat, mesh] : by_material) {
      mesh.name = shape.name;
      mesh.material = mat;
      // Corners mixing "has normal" and "has none" leave the arrays short: recompute then.
      if (mesh.normals.size() != mesh.positions.size()) mesh.normals.clear();
      if (mesh.uvs.size() != mesh.positions.size()) mesh.uvs.clear();
      if (Status s = detail::finish_mesh(mesh, path); !s.ok()) return s;
      scene.meshes.push_back(std::move(mesh));
    }
  }
  if (scene.meshes.empty()) {
    return Status::error(ErrorCode::corrupt_data, path + ": OBJ file has no faces");
  }
  scene.update_bounds();
  return scene;
}

}  // namespace tessera::scene
