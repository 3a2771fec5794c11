// Driver: quad meshes, OBJ polygons, directed-edge adjacency and valence-4 corner links.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include "core/check.h"
#include "scene/scene_internal.h"
#include "tessera/faces.h"

namespace tessera::faces {

namespace {

/// Edge midpoints, each made once: `mid(a, b)` is the index in `out` of the midpoint of vertices
/// a and b of `in`, appended to `out` the first time the edge (either way round) is asked for.
class EdgeMidpoints {
 public:
  EdgeMidpoints(const std::vector<Vec3>& in, std::vector<Vec3>& out) : in_(in), out_(out) {}

  int operator()(int a, int b) {
    const std::uint64_t k =
        (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
    auto it = mids_.find(k);
    if (it != mids_.end()) return it->second;
    const int id = int(out_.size());
    out_.push_back((in_[std::size_t(a)] + in_[std::size_t(b)]) * 0.5f);
    mids_.emplace(k, id);
    return id;
  }

 private:
  const std::vector<Vec3>& in_;
  std::vector<Vec3>& out_;
  std::unordered_map<std::uint64_t, int> mids_;
};

}  // namespace

Vec3 QuadMesh::point(int face, texture::Uv uv) const {
  const std::array<int, 4>& q = quads[std::size_t(face)];
  const Vec3& p0 = positions[std::size_t(q[0])];
  const Vec3& p1 = positions[std::size_t(q[1])];
  const Vec3& p2 = positions[std::size_t(q[2])];
  const Vec3& p3 = positions[std::size_t(q[3])];
  const float u = uv.u, v = uv.v;
  return p0 * ((1 - u) * (1 - v)) + p1 * (u * (1 - v)) + p2 * (u * v) + p3 * ((1 - u) * v);
}

Result<PolygonMesh> load_obj_polygons(const std::string& path) {
  // The same OBJ reader as the scene loader (tinyobjloader), without triangulation: Ptex face
  // ids follow the file's faces, of any vertex count.
  if (std::FILE* probe = std::fopen(path.c_str(), "rb")) {
    std::fclose(probe);
  } else {
    return Status::error(ErrorCode::io_error, path + ": cannot open: " + std::strerror(errno));
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    return scene::detail::obj_parse_error(path, reader.Error());
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  PolygonMesh mesh;
  mesh.positions.reserve(attrib.vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    mesh.positions.push_back({attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]});
  }
  const long n = long(mesh.positions.size());
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t at = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t count = shape.mesh.num_face_vertices[f];
      if (at + count > shape.mesh.indices.size()) {
        return Status::error(ErrorCode::corrupt_data, path + ": malformed face records");
      }
      std::vector<int> face;
      for (std::size_t k = 0; k < count; ++k) {
        const long idx = shape.mesh.indices[at + k].vertex_index;
        if (idx < 0 || idx >= n) {
          return Status::error(ErrorCode::corrupt_data, path + ": face " +
                                                            std::to_string(mesh.faces.size()) +
                                                            " has a vertex index out of range");
        }
        face.push_back(int(idx));
      }
      at += count;
      if (face.size() < 3) {
        return Status::error(
            ErrorCode::corrupt_data,
            path + ": face " + std::to_string(mesh.faces.size()) + " has fewer than 3 vertices");
      }
      mesh.faces.push_back(std::move(face));
    }
  }
  if (mesh.faces.empty()) return Status::error(ErrorCode::corrupt_data, path + ": no faces");
  return mesh;
}

Result<QuadMesh> to_quad_mesh(const PolygonMesh& mesh, const std::string& name) {
  QuadMesh q;
  q.positions = mesh.positions;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::vector<int>& face = mesh.faces[f];
    if (face.size() != 4) {
      return Status::error(ErrorCode::unsupported,
                           name + ": face " + std::to_string(f) + " has " +
                               std::to_string(face.size()) +
                               " vertices: only all-quad meshes are supported (split non-quad "
                               "faces into quads, e.g. one Catmull-Clark step)");
    }
    q.quads.push_back({face[0], face[1], face[2], face[3]});
  }
  return q;
}

QuadMesh ptex_face_layout(const PolygonMesh& mesh, std::vector<bool>* subface) {
  QuadMesh q;
  q.positions = mesh.positions;
  if (subface) subface->clear();
  EdgeMidpoints mid(mesh.positions, q.positions);
  for (const std::vector<int>& f : mesh.faces) {
    const int n = int(f.size());
    if (n == 4) {
      q.quads.push_back({f[0], f[1], f[2], f[3]});
      if (subface) subface->push_back(false);
      continue;
    }
    Vec3 c;
    for (int v : f) c = c + mesh.positions[std::size_t(v)];
    const int centre = int(q.positions.size());
    q.positions.push_back(c * (1.0f / float(n)));
    for (int i = 0; i < n; ++i) {
      const int prev = f[std::size_t((i + n - 1) % n)], cur = f[std::size_t(i)],
                next = f[std::size_t((i + 1) % n)];
      q.quads.push_back({cur, mid(cur, next), centre, mid(prev, cur)});
      if (subface) subface->push_back(true);
    }
  }
  return q;
}

Result<std::vector<FaceAdjacency>> build_adjacency(const QuadMesh& mesh) {
  // Directed edge (a -> b) -> face * 4 + edge.
  std::unordered_map<std::uint64_t, int> edges;
  edges.reserve(mesh.quads.size() * 4);
  auto key = [](int a, int b) {
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
  };
  const int nverts = int(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.quads.size(); ++f) {
    for (int e = 0; e < 4; ++e) {
      const int a = mesh.quads[f][std::size_t(e)], b = mesh.quads[f][std::size_t((e + 1) & 3)];
      if (a < 0 || b < 0 || a >= nverts || b >= nverts) {
        return Status::error(ErrorCode::invalid_argument,
                             "face " + std::to_string(f) + ": vertex index out of range");
      }
      if (a == b) {
        return Status::error(
            ErrorCode::invalid_argument,
            "face " + std::to_string(f) + ": degenerate edge " + std::to_string(e));
      }
      if (!edges.emplace(key(a, b), int(f) * 4 + e).second) {
        return Status::error(ErrorCode::invalid_argument,
                             "face " + std::to_string(f) + " edge " + std::to_string(e) +
                                 ": directed edge used twice (inconsistent orientation or "
                                 "non-manifold mesh)");
      }
    }
  }
  std::vector<FaceAdjacency> adj(mesh.quads.size());
  for (std::size_t f = 0; f < mesh.quads.size(); ++f) {
    for (int e = 0; e < 4; ++e) {
      const int a = mesh.quads[f][std::size_t(e)], b = mesh.quads[f][std::size_t((e + 1) & 3)];
      auto it = edges.find(key(b, a));
      if (it == edges.end()) continue;
      adj[f].face[std::size_t(e)] = it->second / 4;
      adj[f].edge[std::size_t(e)] = it->second % 4;
    }
  }
  // Adjacency is mutual: across my edge e lies face n's edge k, and across n's edge k lies me.
  for (std::size_t f = 0; f < adj.size(); ++f) {
    for (std::size_t e = 0; e < 4; ++e) {
      const int n = adj[f].face[e];
      if (n < 0) continue;
      TESSERA_DCHECK(std::size_t(n) < adj.size() && adj[f].edge[e] >= 0 && adj[f].edge[e] < 4);
      TESSERA_DCHECK(adj[std::size_t(n)].face[std::size_t(adj[f].edge[e])] == int(f));
      TESSERA_DCHECK(adj[std::size_t(n)].edge[std::size_t(adj[f].edge[e])] == int(e));
    }
  }
  return adj;
}

std::vector<std::array<CornerLink, 4>> corner_links(const std::vector<FaceAdjacency>& adjacency) {
  std::vector<std::array<CornerLink, 4>> links(adjacency.size());
  const int n = int(adjacency.size());
  for (int f = 0; f < n; ++f) {
    for (int c = 0; c < 4; ++c) {
      // Corner c is the start of edge c and the end of edge c - 1. Walk around the vertex:
      // across my edge c, then in each face across the edge after the shared one.
      int face = f, edge = c;
      int faces[4];
      int in_edges[4];
      bool ok = true;
      UvTransform t;
      for (int step = 0; step < 4 && ok; ++step) {
        const FaceAdjacency& a = adjacency[std::size_t(face)];
        const int nb = a.face[std::size_t(edge)];
        if (nb < 0 || nb >= n) {
          ok = false;
          break;
        }
        const int nb_edge = a.edge[std::size_t(edge)];
        if (step < 2) t = t.then(edge_transform(edge, nb_edge));
        faces[step] = nb;
        in_edges[step] = nb_edge;
        face = nb;
        edge = (nb_edge + 1) & 3;
      }
      // Valence 4: four steps return to me, entering across my edge c - 1.
      if (!ok || faces[3] != f || in_edges[3] != ((c + 3) & 3) || faces[1] == f) continue;
      links[std::size_t(f)][std::size_t(c)].face = faces[1];
      links[std::size_t(f)][std::size_t(c)].transform = t;
    }
  }
  return links;
}

std::array<int, 16> edge_pairing_histogram(const std::vector<FaceAdjacency>& adjacency) {
  std::array<int, 16> h{};
  for (const FaceAdjacency& a : adjacency) {
    for (int e = 0; e < 4; ++e) {
      if (a.face[std::size_t(e)] >= 0) ++h[std::size_t(e * 4 + a.edge[std::size_t(e)])];
    }
  }
  return h;
}

QuadMesh subdivide(const QuadMesh& mesh) {
  QuadMesh out;
  out.positions = mesh.positions;
  EdgeMidpoints mid(mesh.positions, out.positions);
  for (int f = 0; f < mesh.face_count(); ++f) {
    const std::array<int, 4>& q = mesh.quads[std::size_t(f)];
    const int ab = mid(q[0], q[1]), bc = mid(q[1], q[2]), cd = mid(q[2], q[3]),
              da = mid(q[3], q[0]);
    const int c = int(out.positions.size());
    out.positions.push_back(mesh.point(f, {0.5f, 0.5f}));
    out.quads.push_back({q[0], ab, c, da});
    out.quads.push_back({ab, q[1], bc, c});
    out.quads.push_back({c, bc, q[2], cd});
    out.quads.push_back({da, c, cd, q[3]});
  }
  return out;
}

void randomise_orientation(QuadMesh& mesh, std::uint32_t seed) {
  std::uint32_t s = seed * 2654435761u + 12345u;
  for (std::array<int, 4>& q : mesh.quads) {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    const int r = int((s >> 7) & 3);
    std::array<int, 4> o;
    for (int i = 0; i < 4; ++i) o[std::size_t(i)] = q[std::size_t((i + r) & 3)];
    q = o;
  }
}

}  // namespace tessera::faces
