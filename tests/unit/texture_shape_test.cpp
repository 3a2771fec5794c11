// Cube maps, arrays and cube map arrays (label `unit`): the shape model of CompressedTexture,
// PVR v3 and KTX 1.1 round trips and layouts, readers' bad input, decoding one image, and
// compress_images (each image encoded as it would be alone; every bad combination one error).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "tessera/procedural.h"
#include "tessera/texture_file.h"
#include "texture_file_test_util.h"

namespace tessera::texture_file {
namespace {

using test::Bytes;

/// A texture of `faces` x `layers` images of real PVRTC data (fast encodes of procedural
/// images, a different one per image) with `levels` levels.
CompressedTexture shaped_texture(pvrtc::Format format, int size, int levels, int faces, int layers,
                                 bool array) {
  CompressedTexture t;
  t.format = format;
  t.width = size;
  t.height = size;
  t.has_alpha = true;
  t.faces = faces;
  t.layers = layers;
  t.array = array;
  t.levels.resize(std::size_t(levels));
  pvrtc::EncodeOptions eo;
  eo.format = format;
  eo.quality = pvrtc::Quality::fast;
  eo.force_alpha = true;
  const Procedural kinds[] = {Procedural::noise, Procedural::bricks, Procedural::foliage,
                              Procedural::gradient, Procedural::text};
  for (int l = 0; l < levels; ++l) {
    for (int i = 0; i < faces * layers; ++i) {
      const int s = mip_dimension(size, l);
      Result<Bytes> enc = pvrtc::encode(make_procedural(kinds[i % 5], s, s, std::uint32_t(i)), eo);
      EXPECT_TRUE(enc.ok());
      t.levels[std::size_t(l)].insert(t.levels[std::size_t(l)].end(), enc->begin(), enc->end());
    }
  }
  return t;
}

void expect_same_shape(const CompressedTexture& a, const CompressedTexture& b) {
  test::expect_same(a, b);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.layers, b.layers);
  EXPECT_EQ(a.array, b.array);
}

std::uint32_t u32(const Bytes& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
void put_u32(Bytes& b, std::size_t at, std::uint32_t v) { std::memcpy(b.data() + at, &v, 4); }

TEST(TextureShape, ImagesAreLayerMajorThenFace) {
  const CompressedTexture t =
      shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 2, 6, 2, /*array=*/true);
  ASSERT_TRUE(validate_texture(t, "t").ok());
  EXPECT_EQ(t.image_count(), 12);
  EXPECT_EQ(t.image_size(0), 128u);
  EXPECT_EQ(t.image_size(1), 32u);
  const std::span<const std::uint8_t> img = t.image(1, 1, 3);  // layer 1, face 3 of level 1
  EXPECT_EQ(img.data(), t.levels[1].data() + (1 * 6 + 3) * 32);
  EXPECT_EQ(img.size(), 32u);
  EXPECT_EQ(texture_shape_name(t), "cube map array of 2 layers");
}

TEST(TextureShape, IndexErrorsNameTheRange) {
  const CompressedTexture cube = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 8, 1, 6, 1, false);
  EXPECT_EQ(check_image_index(cube, 0, 0, 6).message,
            "face 6 is out of range (the cube map has faces 0 to 5)");
  EXPECT_EQ(check_image_index(cube, 0, 1, 0).message,
            "layer 1 is out of range (the texture is not an array: layer 0 only)");
  EXPECT_EQ(check_image_index(cube, 1, 0, 0).message,
            "level 1 is out of range (the texture has levels 0 to 0)");
  const CompressedTexture arr = shaped_texture(pvrtc::Format::pvrtc1_2bpp, 16, 1, 1, 3, true);
  EXPECT_EQ(check_image_index(arr, 0, 3, 0).message,
            "layer 3 is out of range (the array has layers 0 to 2)");
  EXPECT_EQ(check_image_index(arr, 0, 0, 1).message,
            "face 1 is out of range (the texture is not a cube map: face 0 only)");
  EXPECT_TRUE(check_image_index(arr, 0, 2, 0).ok());
  EXPECT_FALSE(decode_texture_image(arr, 0, 3, 0).ok());
}

TEST(TextureShape, ValidateRejectsImpossibleShapes) {
  CompressedTexture t = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 1, 6, 1, false);
  t.faces = 5;
  EXPECT_FALSE(validate_texture(t, "t").ok());
  t = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 1, 1, 2, false);  // layers without array
  EXPECT_NE(validate_texture(t, "t").message.find("more than 1 only in an array"),
            std::string::npos);
  t = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 1, 1, 2, true);
  t.levels[0].resize(t.levels[0].size() - 8);  // one block short
  EXPECT_NE(validate_texture(t, "t").message.find("expected 256"), std::string::npos);
  t = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 1, 6, 1, false);
  t.height = 8;
  EXPECT_NE(validate_texture(t, "t").message.find("must be square"), std::string::npos);
}

TEST(TextureShape, EveryShapeRoundTripsThroughPvrAndKtx) {
  struct Case {
    int faces, layers;
    bool array;
  };
  for (const Case c : {Case{6, 1, false}, Case{1, 3, true}, Case{1, 1, true}, Case{6, 2, true}}) {
    for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
      CompressedTexture t = shaped_texture(f, 16, 3, c.faces, c.layers, c.array);
      t.premultiplied = true;
      t.srgb = c.layers == 3;
      SCOPED_TRACE(texture_shape_name(t));
      Result<CompressedTexture> ktx = parse_ktx1(test::ktx_bytes(t), "t.ktx");
      ASSERT_TRUE(ktx.ok()) << ktx.status().message;
      ktx->premultiplied = true;  // KTX 1.1 has no premultiplied flag
      expect_same_shape(*ktx, t);
      Result<CompressedTexture> pvr = parse_pvr3(test::pvr_bytes(t), "t.pvr");
      ASSERT_TRUE(pvr.ok()) << pvr.status().message;
      EXPECT_TRUE(pvr->premultiplied);
      // PVR v3 has no array flag: one surface reads back as a plain texture.
      if (c.layers == 1) pvr->array = c.array;
      expect_same_shape(*pvr, t);
    }
  }
}

TEST(TextureShape, HeadersSayFacesAndLayers) {
  const CompressedTexture cube = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 2, 6, 1, false);
  const Bytes pvr = test::pvr_bytes(cube);
  EXPECT_EQ(u32(pvr, 36), 1u);  // surfaces
  EXPECT_EQ(u32(pvr, 40), 6u);  // faces
  const Bytes ktx = test::ktx_bytes(cube);
  EXPECT_EQ(u32(ktx, 12 + 4 * 9), 0u);   // numberOfArrayElements: not an array
  EXPECT_EQ(u32(ktx, 12 + 4 * 10), 6u);  // numberOfFaces
  // A cube map that is not an array: imageSize is one face (128 bytes at 16x16 4 bpp), and
  // the six faces follow.
  const std::size_t level0 = 64 + u32(ktx, 12 + 4 * 12);
  EXPECT_EQ(u32(ktx, level0), 128u);
  EXPECT_EQ(std::memcmp(ktx.data() + level0 + 4, cube.levels[0].data(), 768), 0);
  EXPECT_EQ(u32(ktx, level0 + 4 + 768), 32u);  // level 1: 32 bytes per face

  const CompressedTexture arr = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 16, 1, 6, 2, true);
  const Bytes ktx_arr = test::ktx_bytes(arr);
  EXPECT_EQ(u32(ktx_arr, 12 + 4 * 9), 2u);
  EXPECT_EQ(u32(ktx_arr, 12 + 4 * 10), 6u);
  EXPECT_EQ(u32(ktx_arr, 64 + u32(ktx_arr, 12 + 4 * 12)), 12u * 128u);  // the whole level
  const Bytes pvr_arr = test::pvr_bytes(arr);
  EXPECT_EQ(u32(pvr_arr, 36), 2u);
  EXPECT_EQ(u32(pvr_arr, 40), 6u);
}

TEST(TextureShape, EveryTruncationIsRejected) {
  const CompressedTexture cube = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 8, 2, 6, 1, false);
  for (const Bytes& file : {test::ktx_bytes(cube), test::pvr_bytes(cube)}) {
    for (std::size_t n = 0; n < file.size(); ++n) {
      const Bytes cut(file.begin(), file.begin() + std::ptrdiff_t(n));
      EXPECT_FALSE(parse_texture(cut, "cut").ok()) << n;
    }
    EXPECT_TRUE(parse_texture(file, "whole").ok());
  }
}

TEST(TextureShape, HeaderLiesAreRejected) {
  const CompressedTexture cube = shaped_texture(pvrtc::Format::pvrtc1_4bpp, 8, 1, 6, 1, false);
  auto expect_error = [](Bytes b, std::size_t at, std::uint32_t v, const char* words) {
    put_u32(b, at, v);
    Result<CompressedTexture> r = parse_texture(b, "lie");
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.status().message.find(words), std::string::npos) << r.status().message;
    EXPECT_EQ(r.status().message.rfind("lie: ", 0), 0u);
  };
  const Bytes pvr = test::pvr_bytes(cube);
  expect_error(pvr, 40, 5, "5 faces are not supported");
  expect_error(pvr, 36, 0, "0 surfaces");
  expect_error(pvr, 36, 0xFFFFFFFFu, "4294967295 surfaces");
  expect_error(pvr, 36, 2, "truncated");  // two layers' data promised, one present
  expect_error(pvr, 24, 4, "not square");
  const Bytes ktx = test::ktx_bytes(cube);
  expect_error(ktx, 12 + 4 * 10, 2, "2 faces are not supported");
  expect_error(ktx, 12 + 4 * 9, 0x7FFFFFFFu, "array elements");
  expect_error(ktx, 12 + 4 * 9, 1, "imageSize 32 does not match");  // an array: whole level
  expect_error(ktx, 12 + 4 * 7, 4, "not square");
}

TEST(TextureShape, ReadsPvrTexToolLayoutOfKtxCubeMaps) {
  // A hand-made KTX 1.1 cube map as the specification lays it out (per level: imageSize of one
  // face, then the 6 faces, each padded to 4): its faces land in order.
  const CompressedTexture cube = shaped_texture(pvrtc::Format::pvrtc1_2bpp, 16, 1, 6, 1, false);
  Result<CompressedTexture> back = parse_ktx1(test::ktx_bytes(cube), "c.ktx");
  ASSERT_TRUE(back.ok());
  for (int f = 0; f < 6; ++f) {
    const auto a = back->image(0, 0, f), b = cube.image(0, 0, f);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << f;
  }
}

// ---------------------------------------------------------------------------------------------
// compress_images
// ---------------------------------------------------------------------------------------------

std::vector<std::string> names_of(int n) {
  std::vector<std::string> v;
  for (int i = 0; i < n; ++i) v.push_back("img" + std::to_string(i) + ".png");
  return v;
}

TEST(CompressImages, EachImageIsEncodedAsItWouldBeAlone) {
  CompressOptions o;
  o.encode.quality = pvrtc::Quality::fast;
  o.mipmaps = true;
  o.mip_levels = 3;
  std::vector<ImageRGBA8> faces;
  for (int i = 0; i < 6; ++i) {
    faces.push_back(make_procedural(i == 2 ? Procedural::foliage : Procedural::noise, 32, 32,
                                    std::uint32_t(i)));
  }
  const std::vector<std::string> names = names_of(6);
  Result<CompressedImage> cube = compress_images(faces, TextureShape{6, false}, o, names);
  ASSERT_TRUE(cube.ok()) << cube.status().message;
  EXPECT_EQ(cube->texture.faces, 6);
  EXPECT_EQ(cube->texture.level_count(), 3);
  EXPECT_TRUE(cube->texture.has_alpha);  // face 2 (foliage) has alpha
  ASSERT_EQ(cube->sources.size(), 6u);
  ASSERT_TRUE(validate_texture(cube->texture, "cube").ok());
  for (int i = 0; i < 6; ++i) {
    Result<CompressedImage> alone = compress_image(faces[std::size_t(i)], o, names[std::size_t(i)]);
    ASSERT_TRUE(alone.ok());
    for (int l = 0; l < 3; ++l) {
      const auto a = cube->texture.image(l, 0, i), b = alone->texture.image(l);
      EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << i << " " << l;
    }
    EXPECT_EQ(cube->sources[std::size_t(i)].pixels, alone->sources.front().pixels);
  }
}

TEST(CompressImages, ArraysAndCubeArrays) {
  CompressOptions o;
  o.encode.quality = pvrtc::Quality::fast;
  o.encode.format = pvrtc::Format::pvrtc1_2bpp;
  std::vector<ImageRGBA8> imgs;
  for (int i = 0; i < 12; ++i)
    imgs.push_back(make_procedural(Procedural::bricks, 16, 16, std::uint32_t(i)));
  Result<CompressedImage> arr =
      compress_images(std::vector<ImageRGBA8>(imgs.begin(), imgs.begin() + 3),
                      TextureShape{1, true}, o, names_of(3));
  ASSERT_TRUE(arr.ok()) << arr.status().message;
  EXPECT_EQ(arr->texture.layers, 3);
  EXPECT_TRUE(arr->texture.array);
  EXPECT_FALSE(arr->texture.has_alpha);
  Result<CompressedImage> cube_array =
      compress_images(imgs, TextureShape{6, true}, o, names_of(12));
  ASSERT_TRUE(cube_array.ok()) << cube_array.status().message;
  EXPECT_EQ(cube_array->texture.layers, 2);
  EXPECT_EQ(cube_array->texture.faces, 6);
  EXPECT_EQ(texture_shape_name(cube_array->texture), "cube map array of 2 layers");
}

TEST(CompressImages, BadSetsAreOneLineErrors) {
  CompressOptions o;
  o.encode.quality = pvrtc::Quality::fast;
  auto error = [&](std::vector<ImageRGBA8> imgs, TextureShape shape) {
    const std::vector<std::string> names = names_of(int(imgs.size()));
    Result<CompressedImage> r = compress_images(std::move(imgs), shape, o, names);
    EXPECT_FALSE(r.ok());
    return r.ok() ? std::string() : r.status().message;
  };
  const ImageRGBA8 a = make_procedural(Procedural::noise, 16, 16);
  const ImageRGBA8 wide = make_procedural(Procedural::noise, 32, 16);
  const ImageRGBA8 big = make_procedural(Procedural::noise, 32, 32);
  EXPECT_EQ(error(std::vector<ImageRGBA8>(7, a), {6, false}),
            "a cube map takes exactly 6 faces (+X, -X, +Y, -Y, +Z, -Z), not 7 (with array: 6 "
            "per layer)");
  EXPECT_EQ(error(std::vector<ImageRGBA8>(6, wide), {6, false}),
            "img0.png: 32x16 is not square (cube map faces must be)");
  EXPECT_EQ(error({a, a, big}, {1, true}),
            "img2.png: 32x32, but img0.png is 16x16 (every face and layer needs one size)");
  EXPECT_EQ(error(std::vector<ImageRGBA8>(8, a), {6, true}),
            "a cube map array takes 6 faces per layer: 8 images is not a multiple of 6");
  EXPECT_EQ(error({a, a}, {1, false}), "2 images for one 2D texture (use array)");
  EXPECT_EQ(error({}, {1, true}), "no images to compress");
  o.normal_map = true;
  o.srgb = true;
  EXPECT_EQ(error({a}, {1, false}),
            "normal_map and srgb: a normal map holds vectors, never sRGB colour");
  o.normal_map = o.srgb = false;
  o.premultiply = o.alpha_bleed = true;
  EXPECT_NE(error({a}, {1, false}).find("alpha_bleed applies to straight alpha"),
            std::string::npos);
}

}  // namespace
}  // namespace tessera::texture_file
