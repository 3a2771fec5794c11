// The GPU layout of per-face textures (tessera/faces_gpu.h), shared by the GL and Vulkan
// backends: one texture array per face resolution, one std430 record per face mirroring the CPU
// FaceTextureSet's adjacency and corner links; and the quad mesh of a Ptex file's faces.
#include <map>
#include <string>
#include <utility>

#include "core/check.h"
#include "tessera/faces.h"
#include "tessera/faces_gpu.h"
#include "tessera/ptex.h"

namespace tessera::faces {

Result<PackedFaces> pack_faces(const FaceTextureSet& set, const PackLimits& limits,
                               const PackLimitNames& names) {
  const int n = set.face_count();
  if (n == 0) return Status::error(ErrorCode::invalid_argument, "pack_faces: no faces");
  // Classes ordered by (height, width).
  std::map<std::pair<int, int>, int> class_of;
  for (int f = 0; f < n; ++f) {
    const texture::Texture& t = set.texture(f);
    if (limits.max_texture_size > 0 &&
        (t.width() > limits.max_texture_size || t.height() > limits.max_texture_size)) {
      return Status::error(ErrorCode::too_large,
                           "face " + std::to_string(f) + " is " + std::to_string(t.width()) + "x" +
                               std::to_string(t.height()) + ", above " + names.texture_size +
                               " = " + std::to_string(limits.max_texture_size));
    }
    class_of.emplace(std::make_pair(t.height(), t.width()), 0);
  }
  PackedFaces p;
  for (auto& [size, index] : class_of) {
    index = int(p.classes.size());
    FaceClass c;
    c.width = size.second;
    c.height = size.first;
    p.classes.push_back(c);
  }
  if (limits.max_classes > 0 && int(p.classes.size()) > limits.max_classes) {
    return Status::error(ErrorCode::too_large,
                         std::to_string(p.classes.size()) +
                             " face resolutions need as many texture arrays, above the limit " +
                             std::to_string(limits.max_classes));
  }
  const std::int64_t bytes = std::int64_t(n) * std::int64_t(sizeof(FaceRecord));
  if (limits.max_ssbo_bytes > 0 && bytes > limits.max_ssbo_bytes) {
    return Status::error(ErrorCode::too_large, std::to_string(n) + " face records (" +
                                                   std::to_string(bytes) + " bytes) exceed " +
                                                   names.ssbo_bytes + " = " +
                                                   std::to_string(limits.max_ssbo_bytes));
  }
  p.records.resize(std::size_t(n));
  for (int f = 0; f < n; ++f) {
    const texture::Texture& t = set.texture(f);
    const int cls = class_of.at({t.height(), t.width()});
    FaceClass& c = p.classes[std::size_t(cls)];
    if (c.faces.empty()) {
      c.levels = t.level_count();
    } else if (c.levels != t.level_count()) {
      return Status::error(ErrorCode::invalid_argument,
                           "face " + std::to_string(f) + " has " + std::to_string(t.level_count()) +
                               " mip levels, other " + std::to_string(t.width()) + "x" +
                               std::to_string(t.height()) + " faces " + std::to_string(c.levels));
    }
    FaceRecord& r = p.records[std::size_t(f)];
    r.info = {cls, int(c.faces.size()), t.width(), t.height()};
    c.faces.push_back(f);
    const FaceAdjacency& a = set.adjacency(f);
    for (int e = 0; e < 4; ++e) {
      const std::size_t ei = std::size_t(e);
      if (a.face[ei] < 0) continue;
      r.neighbour[ei] = a.face[ei];
      r.mapping[ei] = e * 4 + a.edge[ei];
    }
    // Corner c: across my edge c into face f1 (entered by its edge e1), then across f1's next
    // edge (e1 + 1) & 3 — the walk corner_links composes.
    for (int c4 = 0; c4 < 4; ++c4) {
      const CornerLink& link = set.corner(f, c4);
      if (link.face < 0) continue;
      const int f1 = a.face[std::size_t(c4)];
      const int e1 = a.edge[std::size_t(c4)];
      const int out1 = (e1 + 1) & 3;
      const int e2 = set.adjacency(f1).edge[std::size_t(out1)];
      r.corner[std::size_t(c4)] = link.face;
      r.corner_mapping[std::size_t(c4)] = (c4 * 4 + e1) * 16 + out1 * 4 + e2;
    }
    // The record as seams.glsl reads it: a class and layer that exist, neighbours that are
    // faces, mappings into the 16 edge transforms (corners: two of them).
    TESSERA_DCHECK(r.info[0] >= 0 && r.info[0] < int(p.classes.size()) && r.info[1] >= 0);
    for (std::size_t e = 0; e < 4; ++e) {
      TESSERA_DCHECK(r.neighbour[e] < n && (r.neighbour[e] < 0) == (r.mapping[e] < 0));
      TESSERA_DCHECK(r.mapping[e] < 16 && r.corner[e] < n && r.corner_mapping[e] < 256);
    }
  }
  for (const FaceClass& c : p.classes) {
    if (limits.max_array_layers > 0 && int(c.faces.size()) > limits.max_array_layers) {
      return Status::error(ErrorCode::too_large,
                           std::to_string(c.faces.size()) + " faces of " + std::to_string(c.width) +
                               "x" + std::to_string(c.height) + " exceed " + names.array_layers +
                               " = " + std::to_string(limits.max_array_layers));
    }
  }
  return p;
}

Result<QuadMesh> ptex_quad_mesh(const PolygonMesh& mesh, const ptex::PtexFile& file,
                                const std::string& name) {
  if (file.mesh_type != ptex::MeshType::quad) {
    return Status::error(ErrorCode::unsupported,
                         name + ": a triangle-mesh Ptex file: only quad-mesh files are supported");
  }
  const int count = file.face_count();
  int next = 0;  // the Ptex face of the polygon's first quad
  for (std::size_t p = 0; p < mesh.faces.size(); ++p) {
    const int n = int(mesh.faces[p].size());
    const int quads = n == 4 ? 1 : n;
    const bool split = n != 4;
    if (next + quads > count) {
      return Status::error(ErrorCode::size_mismatch,
                           name + ": the mesh's polygons make more than the Ptex file's " +
                               std::to_string(count) + " faces (polygon " + std::to_string(p) +
                               ")");
    }
    for (int k = 0; k < quads; ++k) {
      const bool sub = file.faces[std::size_t(next + k)].subface;
      if (split && !sub) {
        return Status::error(
            ErrorCode::unsupported,
            name + ": polygon " + std::to_string(p) + " has " + std::to_string(n) +
                " vertices, but Ptex face " + std::to_string(next + k) +
                " is not a subface: only quads, and n-gons the Ptex file split into subfaces, "
                "are supported");
      }
      if (!split && sub) {
        return Status::error(ErrorCode::size_mismatch, name + ": polygon " + std::to_string(p) +
                                                           " is a quad, but Ptex face " +
                                                           std::to_string(next) +
                                                           " is a subface of a split polygon");
      }
    }
    next += quads;
  }
  if (next != count) {
    return Status::error(ErrorCode::size_mismatch,
                         name + ": the mesh's polygons make " + std::to_string(next) +
                             " Ptex faces, the file has " + std::to_string(count));
  }
  return ptex_face_layout(mesh);
}

std::vector<FaceClassDraw> class_grouped_indices(const PackedFaces& layout, bool reversed,
                                                 std::vector<std::uint32_t>& indices) {
  std::vector<FaceClassDraw> draws;
  for (std::size_t c = 0; c < layout.classes.size(); ++c) {
    const FaceClassDraw start{int(c), indices.size(), 0};
    for (int f : layout.classes[c].faces) {
      const std::uint32_t b = std::uint32_t(f) * 4;
      const std::array<std::uint32_t, 6> tri =
          reversed ? std::array<std::uint32_t, 6>{b, b + 2, b + 1, b, b + 3, b + 2}
                   : std::array<std::uint32_t, 6>{b, b + 1, b + 2, b, b + 2, b + 3};
      indices.insert(indices.end(), tri.begin(), tri.end());
    }
    if (indices.size() > start.first) {
      draws.push_back({start.cls, start.first, indices.size() - start.first});
    }
  }
  return draws;
}

}  // namespace tessera::faces
