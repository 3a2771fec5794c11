// glTF 2.0 loading through tinygltf: node hierarchy, triangle primitives, base-colour
// materials and textures (decoded by tessera's own image readers), point lights.
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>

#include "scene_internal.h"
#include "tessera/io.h"

namespace tessera::scene {

namespace {

constexpr int kTriangles = 4;  // TINYGLTF_MODE_TRIANGLES

struct ImageContext {
  std::string path;
  std::vector<ImageRGBA8>* images;
  std::vector<std::string>* errors;
  bool load;
};

// tinygltf hands us the encoded bytes of each image (file, data URI or GLB buffer view); we
// decode them with tessera's readers (size limits, one-line errors) and keep them ourselves.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto* ctx = static_cast<ImageContext*>(user);
  if (index < 0) return false;
  if (std::size_t(index) >= ctx->images->size()) ctx->images->resize(std::size_t(index) + 1);
  if (!ctx->load) return true;
  const std::string name = ctx->path + ": image " + std::to_string(index) +
                           (image->uri.empty() ? "" : " (" + image->uri + ")");
  Result<ImageRGBA8> img = io::decode_image({bytes, std::size_t(std::max(size, 0))}, name);
  if (!img) {
    if (err) *err = img.status().message;
    ctx->errors->push_back(img.status().message);
    return false;
  }
  (*ctx->images)[std::size_t(index)] = std::move(*img);
  return true;
}

/// Reads `count` elements of `comps` floats from an accessor, validating every range.
Status read_floats(const tinygltf::Model& model, int accessor_index, int comps,
                   std::vector<float>& out, const std::string& what) {
  auto bad = [&](const std::string& why) {
    return Status::error(ErrorCode::corrupt_data,
                         what + ": accessor " + std::to_string(accessor_index) + ": " + why);
  };
  if (accessor_index < 0 || std::size_t(accessor_index) >= model.accessors.size()) {
    return bad("does not exist");
  }
  const tinygltf::Accessor& acc = model.accessors[std::size_t(accessor_index)];
  const int type_comps = tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
  if (type_comps != comps)
    return bad("has " + std::to_string(type_comps) + " components, expected " +
               std::to_string(comps));
  if (acc.bufferView < 0 || std::size_t(acc.bufferView) >= model.bufferViews.size()) {
    return bad("has no buffer view (sparse accessors are not supported)");
  }
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(acc.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) return bad("bad buffer");
  const auto& data = model.buffers[std::size_t(view.buffer)].data;
  const int csize = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
  if (csize <= 0) return bad("unknown component type");
  const std::size_t elem = std::size_t(csize) * std::size_t(comps);
  const std::size_t stride = view.byteStride ? view.byteStride : elem;
  const std::size_t count = acc.count;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    return bad("buffer view exceeds its buffer");
  }
  if (count > 0 && (acc.byteOffset > view.byteLength ||
                    (count - 1) > (view.byteLength - acc.byteOffset -
                                   std::min(elem, view.byteLength - acc.byteOffset)) /
                                      stride ||
                    acc.byteOffset + (count - 1) * stride + elem > view.byteLength)) {
    return bad("reads past its buffer view");
  }
  out.resize(count * std::size_t(comps));
  const std::uint8_t* base = data.data() + view.byteOffset + acc.byteOffset;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = base + i * stride;
    for (int c = 0; c < comps; ++c) {
      float v = 0.0f;
      const std::uint8_t* q = p + std::size_t(c) * std::size_t(csize);
      switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
          std::memcpy(&v, q, 4);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          v = acc.normalized ? *q / 255.0f : float(*q);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t s;
          std::memcpy(&s, q, 2);
          v = acc.normalized ? s / 65535.0f : float(s);
          break;
        }
        default:
          return bad("unsupported component type for a vertex attribute");
      }
      out[i * std::size_t(comps) + std::size_t(c)] = v;
    }
  }
  return Status::success();
}

Status read_indices(const tinygltf::Model& model, int accessor_index,
                    std::vector<std::uint32_t>& out, const std::string& what) {
  auto bad = [&](const std::string& why) {
    return Status::error(ErrorCode::corrupt_data,
                         what + ": index accessor " + std::to_string(accessor_index) + ": " + why);
  };
  if (accessor_index < 0 || std::size_t(accessor_index) >= model.accessors.size())
    return bad("does not exist");
  const tinygltf::Accessor& acc = model.accessors[std::size_t(accessor_index)];
  if (acc.type != TINYGLTF_TYPE_SCALAR) return bad("is not scalar");
  if (acc.bufferView < 0 || std::size_t(acc.bufferView) >= model.bufferViews.size())
    return bad("has no buffer view");
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(acc.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) return bad("bad buffer");
  const auto& data = model.buffers[std::size_t(view.buffer)].data;
  const int csize = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
  if (csize != 1 && csize != 2 && csize != 4) return bad("unsupported index type");
  const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(csize);
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    return bad("buffer view exceeds its buffer");
  }
  const std::size_t count = acc.count;
  if (count > 0 && (acc.byteOffset > view.byteLength ||
                    (count - 1) > (view.byteLength - acc.byteOffset) / stride ||
                    acc.byteOffset + (count - 1) * stride + std::size_t(csize) > view.byteLength)) {
    return bad("reads past its buffer view");
  }
  out.resize(count);
  const std::uint8_t* base = data.data() + view.byteOffset + acc.byteOffset;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = base + i * stride;
    if (csize == 1) {
      out[i] = *p;
    } else if (csize == 2) {
      std::uint16_t s;
      std::memcpy(&s, p, 2);
      out[i] = s;
    } else {
      std::memcpy(&out[i], p, 4);
    }
  }
  return Status::success();
}

Mat4 node_matrix(const tinygltf::Node& node) {
  Mat4 m;
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m.m[c][r] = float(node.matrix[std::size_t(c * 4 + r)]);
    }
    return m;
  }
  if (node.translation.size() == 3) {
    m = m * translation({float(node.translation[0]), float(node.translation[1]),
                         float(node.translation[2])});
  }
  if (node.rotation.size() == 4) {
    m = m * rotation_quat(float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]),
                          float(node.rotation[3]));
  }
  if (node.scale.size() == 3) {
    m = m * scaling({float(node.scale[0]), float(node.scale[1]), float(node.scale[2])});
  }
  return m;
}

/// tinygltf's model of `path` and its images decoded by tessera's readers (ImageContext).
Status load_model(const std::string& path, const LoadOptions& options, tinygltf::Model& model,
                  std::vector<ImageRGBA8>& images) {
  tinygltf::TinyGLTF loader;
  std::vector<std::string> image_errors;
  ImageContext ctx{path, &images, &image_errors, options.load_textures};
  loader.SetImageLoader(load_image, &ctx);
  std::string err, warn;
  const bool glb = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                        path.compare(path.size() - 4, 4, ".GLB") == 0);
  {
    // tinygltf reads whole files itself; refuse a missing one with our usual wording first.
    Result<std::vector<std::uint8_t>> probe = io::read_file(path, 1);
    if (!probe && probe.status().code == ErrorCode::io_error) return probe.status();
  }
  const bool ok = glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                      : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!image_errors.empty()) return Status::error(ErrorCode::corrupt_data, image_errors.front());
  if (!ok) {
    std::string why = err.empty() ? "parse error" : err;
    for (char& c : why) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    while (!why.empty() && why.back() == ' ') why.pop_back();
    return Status::error(ErrorCode::corrupt_data, path + ": cannot read glTF: " + why);
  }
  return Status::success();
}

/// The scene of a loaded model: materials and textures, then the node tree from its roots
/// (lights and triangle meshes placed by their nodes' transforms).
class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::vector<ImageRGBA8>& images,
               const std::string& path, const LoadOptions& options)
      : model_(model),
        images_(images),
        path_(path),
        options_(options),
        texture_map_(model.textures.size(), -1),
        depth_guard_(model.nodes.size(), 0) {}

  void add_materials();
  /// The node and its subtree under the world transform `parent`.
  Status visit(int node_index, const Mat4& parent);
  Scene take() { return std::move(scene_); }

 private:
  Status corrupt(const std::string& what) const {
    return Status::error(ErrorCode::corrupt_data, path_ + ": " + what);
  }
  int texture_for(int tex_index, bool srgb);
  void add_light(const tinygltf::Node& node, const Mat4& world);
  Status add_primitive(const tinygltf::Mesh& gm, const tinygltf::Primitive& prim, const Mat4& world,
                       const Mat4& normal_matrix);

  const tinygltf::Model& model_;
  const std::vector<ImageRGBA8>& images_;
  const std::string& path_;
  const LoadOptions& options_;
  Scene scene_;
  // Textures: glTF textures point at images; keep one tessera texture per glTF texture.
  std::vector<int> texture_map_;
  std::vector<int> depth_guard_;
  int default_material_ = 0;
  std::size_t triangles_ = 0;
};

int SceneBuilder::texture_for(int tex_index, bool srgb) {
  if (!options_.load_textures || tex_index < 0 ||
      std::size_t(tex_index) >= model_.textures.size()) {
    return -1;
  }
  if (texture_map_[std::size_t(tex_index)] >= 0) return texture_map_[std::size_t(tex_index)];
  const int src = model_.textures[std::size_t(tex_index)].source;
  if (src < 0 || std::size_t(src) >= images_.size() || images_[std::size_t(src)].empty()) {
    return -1;
  }
  texture_map_[std::size_t(tex_index)] = int(scene_.textures.size());
  scene_.textures.push_back({model_.images[std::size_t(src)].uri, images_[std::size_t(src)], srgb});
  return texture_map_[std::size_t(tex_index)];
}

void SceneBuilder::add_materials() {
  for (const tinygltf::Material& m : model_.materials) {
    Material mat;
    mat.name = m.name;
    const auto& f = m.pbrMetallicRoughness.baseColorFactor;
    for (std::size_t c = 0; c < 4 && c < f.size(); ++c) mat.base_color[c] = float(f[c]);
    mat.base_color_texture = texture_for(m.pbrMetallicRoughness.baseColorTexture.index, true);
    mat.normal_texture = texture_for(m.normalTexture.index, false);
    mat.double_sided = m.doubleSided;
    mat.alpha_mask = m.alphaMode == "MASK";
    mat.alpha_blend = m.alphaMode == "BLEND";
    mat.alpha_cutoff = float(m.alphaCutoff);
    scene_.materials.push_back(std::move(mat));
  }
  default_material_ = int(scene_.materials.size());
  scene_.materials.push_back(Material{"default"});
}

// Lights (KHR_lights_punctual), placed by the nodes that reference them.
void SceneBuilder::add_light(const tinygltf::Node& node, const Mat4& world) {
  int light = -1;
  if (auto ext = node.extensions.find("KHR_lights_punctual"); ext != node.extensions.end()) {
    if (ext->second.IsObject() && ext->second.Has("light") && ext->second.Get("light").IsNumber()) {
      light = ext->second.Get("light").GetNumberAsInt();
    }
  }
  if (light < 0 || std::size_t(light) >= model_.lights.size()) return;
  const tinygltf::Light& l = model_.lights[std::size_t(light)];
  if (l.type != "point") return;
  PointLight p;
  p.position = world.transform_point({0, 0, 0});
  for (std::size_t c = 0; c < 3 && c < l.color.size(); ++c) p.color[c] = float(l.color[c]);
  p.intensity = float(l.intensity);
  p.range = float(l.range);
  scene_.lights.push_back(p);
}

Status SceneBuilder::add_primitive(const tinygltf::Mesh& gm, const tinygltf::Primitive& prim,
                                   const Mat4& world, const Mat4& normal_matrix) {
  if (prim.mode != kTriangles) return Status::success();  // points and lines are not rendered
  Mesh mesh;
  mesh.name = gm.name;
  mesh.material =
      (prim.material >= 0 && prim.material < default_material_) ? prim.material : default_material_;
  std::vector<float> pos, nrm, uv;
  auto attr = [&](const char* key) {
    auto it = prim.attributes.find(key);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  if (attr("POSITION") < 0) {
    return corrupt("mesh '" + gm.name + "' has a primitive without POSITION");
  }
  if (Status s = read_floats(model_, attr("POSITION"), 3, pos, path_); !s.ok()) return s;
  if (attr("NORMAL") >= 0) {
    if (Status s = read_floats(model_, attr("NORMAL"), 3, nrm, path_); !s.ok()) return s;
  }
  if (attr("TEXCOORD_0") >= 0) {
    if (Status s = read_floats(model_, attr("TEXCOORD_0"), 2, uv, path_); !s.ok()) return s;
  }
  const std::size_t n = pos.size() / 3;
  mesh.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    mesh.positions[i] = world.transform_point({pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]});
  }
  if (nrm.size() == pos.size()) {
    mesh.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      mesh.normals[i] =
          normal_matrix.transform_vector({nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]});
    }
  }
  if (uv.size() == 2 * n) {
    mesh.uvs.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.uvs[i] = {uv[2 * i], uv[2 * i + 1]};
  }
  if (prim.indices >= 0) {
    if (Status s = read_indices(model_, prim.indices, mesh.indices, path_); !s.ok()) return s;
  } else {
    mesh.indices.resize(n - n % 3);
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = std::uint32_t(i);
  }
  triangles_ += mesh.triangle_count();
  if (triangles_ > options_.max_triangles) {
    return Status::error(
        ErrorCode::too_large,
        path_ + ": more than " + std::to_string(options_.max_triangles) + " triangles");
  }
  if (Status s = detail::finish_mesh(mesh, path_); !s.ok()) return s;
  if (!mesh.indices.empty()) scene_.meshes.push_back(std::move(mesh));
  return Status::success();
}

Status SceneBuilder::visit(int node_index, const Mat4& parent) {
  if (node_index < 0 || std::size_t(node_index) >= model_.nodes.size()) {
    return corrupt("node index " + std::to_string(node_index) + " out of range");
  }
  if (depth_guard_[std::size_t(node_index)]++ > 0) {
    return corrupt("node " + std::to_string(node_index) +
                   " is reached twice (cycle or shared child)");
  }
  const tinygltf::Node& node = model_.nodes[std::size_t(node_index)];
  const Mat4 world = parent * node_matrix(node);
  const Mat4 normal_matrix = transpose(inverse(world));
  add_light(node, world);
  if (node.mesh >= 0) {
    if (std::size_t(node.mesh) >= model_.meshes.size()) {
      return corrupt("node " + std::to_string(node_index) + " refers to a missing mesh");
    }
    const tinygltf::Mesh& gm = model_.meshes[std::size_t(node.mesh)];
    for (const tinygltf::Primitive& prim : gm.primitives) {
      if (Status s = add_primitive(gm, prim, world, normal_matrix); !s.ok()) return s;
    }
  }
  for (int child : node.children) {
    if (Status s = visit(child, world); !s.ok()) return s;
  }
  return Status::success();
}

}  // namespace

Result<Scene> load_gltf(const std::string& path, const LoadOptions& options) {
  tinygltf::Model model;
  std::vector<ImageRGBA8> images;
  if (Status s = load_model(path, options, model, images); !s.ok()) return s;
  SceneBuilder builder(model, images, path, options);
  builder.add_materials();
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && std::size_t(model.defaultScene) < model.scenes.size()
                      ? model.defaultScene
                      : 0;
    roots = model.scenes[std::size_t(s)].nodes;
  } else {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) roots.push_back(int(i));
  }
  for (int r : roots) {
    if (Status s = builder.visit(r, Mat4::identity()); !s.ok()) return s;
  }
  Scene scene = builder.take();
  if (scene.meshes.empty()) {
    return Status::error(ErrorCode::corrupt_data, path + ": glTF file has no triangles");
  }
  scene.update_bounds();
  return scene;
}

}  // namespace tessera::scene
