// Data: per-face texture sets (one mipmapped texture per face, coverage in alpha) from baked
// images or a decoded .ptx file.
#include <algorithm>

#include "tessera/faces.h"
#include "tessera/ptex.h"

namespace tessera::faces {

Result<FaceTextureSet> FaceTextureSet::create(const std::vector<ImageRGBAF>& images,
                                              std::vector<FaceAdjacency> adjacency,
                                              const Parallel& parallel) {
  if (images.size() != adjacency.size()) {
    return Status::error(ErrorCode::size_mismatch, std::to_string(images.size()) +
                                                       " face images for " +
                                                       std::to_string(adjacency.size()) + " faces");
  }
  const int n = int(images.size());
  for (int f = 0; f < n; ++f) {
    for (int e = 0; e < 4; ++e) {
      const int nb = adjacency[std::size_t(f)].face[std::size_t(e)];
      const int ne = adjacency[std::size_t(f)].edge[std::size_t(e)];
      if (nb < -1 || nb >= n || ne < 0 || ne > 3) {
        return Status::error(ErrorCode::invalid_argument,
                             "face " + std::to_string(f) + ": neighbour out of range");
      }
    }
    if (images[std::size_t(f)].empty()) {
      return Status::error(ErrorCode::invalid_argument,
                           "face " + std::to_string(f) + ": empty image");
    }
  }
  FaceTextureSet set;
  set.textures_.resize(std::size_t(n));
  std::vector<Status> errors(static_cast<std::size_t>(n));
  parallel_for(
      0, n, 16,
      [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t f = b; f < e; ++f) {
          ImageRGBAF img = images[std::size_t(f)];
          for (std::size_t i = 0; i < img.pixel_count(); ++i) img.pixels[i * 4 + 3] = 1.0f;
          texture::TextureOptions o;
          o.threads = 1;
          Result<texture::Texture> t = texture::Texture::from_float(img, o);
          if (!t) {
            errors[std::size_t(f)] = t.status();
            continue;
          }
          set.textures_[std::size_t(f)] = std::move(*t);
        }
      },
      parallel);
  for (const Status& s : errors) {
    if (!s.ok()) return s;
  }
  set.corners_ = corner_links(adjacency);
  set.adjacency_ = std::move(adjacency);
  return set;
}

Result<FaceTextureSet> FaceTextureSet::from_ptex(const ptex::PtexFile& file,
                                                 const std::string& name,
                                                 const Parallel& parallel) {
  if (file.mesh_type != ptex::MeshType::quad) {
    return Status::error(ErrorCode::unsupported,
                         name +
                             ": triangle-mesh Ptex files are not supported (per-face "
                             "seamless sampling is implemented for quad faces only)");
  }
  const bool linear =
      file.data_type == ptex::DataType::half || file.data_type == ptex::DataType::f32;
  std::vector<ImageRGBAF> images(file.faces.size());
  std::vector<FaceAdjacency> adj(file.faces.size());
  const int ch = file.channels;
  for (std::size_t f = 0; f < file.faces.size(); ++f) {
    const ptex::FaceInfo& info = file.faces[f];
    ImageRGBAF img(info.width(), info.height());
    const std::vector<float>& src = file.texels[f];
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
      float rgb[3];
      for (int k = 0; k < 3; ++k) {
        const float v = src[i * std::size_t(ch) + std::size_t(ch >= 3 ? k : 0)];
        rgb[k] = linear ? v : srgb_to_linear(v);
      }
      for (int k = 0; k < 3; ++k) img.pixels[i * 4 + std::size_t(k)] = rgb[k];
      img.pixels[i * 4 + 3] = 1.0f;
    }
    images[f] = std::move(img);
    adj[f].face = info.adj_faces;
    adj[f].edge = info.adj_edges;
    // Between a subface and a regular quad the shared edge is a T-junction (one quad edge, two
    // subface half-edges): the 16 full-edge transforms do not apply, so it is a border here.
    for (int e = 0; e < 4; ++e) {
      const int nb = info.adj_faces[std::size_t(e)];
      if (nb >= 0 && file.faces[std::size_t(nb)].subface != info.subface) {
        adj[f].face[std::size_t(e)] = -1;
      }
    }
  }
  return create(images, std::move(adj), parallel);
}

int FaceTextureSet::linked_corner_count() const {
  int n = 0;
  for (const auto& c : corners_) {
    for (const CornerLink& l : c) n += l.face >= 0 ? 1 : 0;
  }
  return n;
}

std::uint64_t FaceTextureSet::texel_count() const {
  std::uint64_t n = 0;
  for (const texture::Texture& t : textures_)
    n += std::uint64_t(t.width()) * std::uint64_t(t.height());
  return n;
}

}  // namespace tessera::faces
