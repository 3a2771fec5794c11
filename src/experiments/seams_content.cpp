// The content of the seam experiment: the built-in Figure-1 scene (optionally with an .obj
// character), or an .obj with its Ptex file, or an .obj with procedural per-face textures.
#include "seams_content.h"

#include <algorithm>
#include <filesystem>

#include "tessera/ptex.h"

namespace tessera::experiments::detail {

namespace fs = std::filesystem;

Result<SeamsContent> load_seams_content(const SeamsConfig& c) {
  SeamsContent l;
  if (c.scene == "figure1") {
    faces::Figure1Options fo = c.figure1;
    if (!c.character.empty()) {
      Result<faces::PolygonMesh> poly = faces::load_obj_polygons(c.character);
      if (!poly) return poly.status();
      // Non-quad faces are split into quads (a triangle mesh: 3 quads per triangle).
      fo.character_mesh = faces::ptex_face_layout(*poly);
      for (int i = 0; i < c.subdivide; ++i) fo.character_mesh = faces::subdivide(fo.character_mesh);
    }
    l.scene = faces::figure1_scene(fo);
    Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(l.scene.mesh);
    if (!adj) return adj.status();
    Result<faces::FaceTextureSet> set = faces::FaceTextureSet::create(
        faces::bake_faces(l.scene, {.scale = 1.0f, .threads = c.threads}), *adj, {c.threads});
    if (!set) return set.status();
    l.set = std::move(*set);
    l.description = "built-in Figure-1 scene: ground plane of " +
                    std::to_string(l.scene.ground_faces) + " faces and " +
                    (c.character.empty() ? std::string("a cube-sphere character")
                                         : c.character + " (" + std::to_string(c.subdivide) +
                                               " subdivision step(s))") +
                    " of " + std::to_string(l.scene.mesh.face_count() - l.scene.ground_faces) +
                    " faces, textures baked from a procedural 3D function";
    return l;
  }
  Result<faces::PolygonMesh> poly = faces::load_obj_polygons(c.scene);
  if (!poly) return poly.status();
  // Quads stay faces; other polygons are split into Ptex subfaces (triangles into 3 quads).
  std::vector<bool> subface;
  l.scene.mesh = faces::ptex_face_layout(*poly, &subface);
  const bool split = std::count(subface.begin(), subface.end(), true) > 0;
  l.scene.name = fs::path(c.scene).stem().string();
  Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(l.scene.mesh);
  if (!adj) return Status::error(adj.status().code, c.scene + ": " + adj.status().message);
  if (!c.ptex.empty()) {
    Result<ptex::PtexFile> file = ptex::read_ptex(c.ptex);
    if (!file) return file.status();
    // Refuses triangle-mesh files before any comparison with the mesh.
    Result<faces::FaceTextureSet> set =
        faces::FaceTextureSet::from_ptex(*file, c.ptex, {c.threads});
    if (!set) return set.status();
    if (file->face_count() != l.scene.mesh.face_count()) {
      return Status::error(ErrorCode::size_mismatch,
                           c.ptex + ": " + std::to_string(file->face_count()) + " faces, but " +
                               c.scene + " has " + std::to_string(l.scene.mesh.face_count()));
    }
    for (const ptex::FaceInfo& fi : file->faces) {
      l.scene.ulog2.push_back(fi.ulog2);
      l.scene.vlog2.push_back(fi.vlog2);
    }
    l.set = std::move(*set);
    l.description = c.scene + " with its Ptex file " + c.ptex + " (adjacency from the file" +
                    (split ? std::string(", non-quad faces split into subfaces)") : ")");
    return l;
  }
  // Procedural textures, resolution from edge lengths, pattern scaled to the mesh size.
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (const Vec3& p : l.scene.mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const float diag = std::max(length(hi - lo), 1e-6f);
  faces::assign_resolutions(l.scene, 400.0f / diag, 2, 7);
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::create(
      faces::bake_faces(l.scene, {.scale = 4.0f / diag, .threads = c.threads}), *adj, {c.threads});
  if (!set) return set.status();
  l.set = std::move(*set);
  l.description = c.scene + (split ? " (non-quad faces split into quads)" : "") +
                  " with procedural per-face textures";
  return l;
}

}  // namespace tessera::experiments::detail
