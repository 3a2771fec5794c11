"""Asset features through the Python module: the new encode keywords, cube maps and arrays, KTX
2.0 with zstd, the Texture's shape fields and pickling, byte for byte against the CLI."""

import json
import pickle
import warnings

import numpy as np
import pytest

import tessera
from conftest import make_image, make_normal_map, run_cli


def write_pngs(tmp_path, images, stem="img"):
    paths = []
    for i, img in enumerate(images):
        paths.append(tmp_path / f"{stem}{i}.png")
        tessera.write_image(paths[-1], img)
    return paths


def cli_bytes(tmp_path, inputs, ext, *flags):
    out = tmp_path / f"cli.{ext}"
    run_cli("compress", *inputs, "-o", out, "-q", *flags)
    return out.read_bytes()


# (CLI flags, encode keywords, image): each new option alone and with others.
KEYWORD_CASES = [
    (["--flip-y"], dict(flip_y=True), "rgba"),
    (["--flip-y", "--mipmaps", "--quality", "fast"], dict(flip_y=True, mipmaps=True,
                                                          quality="fast"), "rgb"),
    (["--premultiply"], dict(premultiply=True), "rgba"),
    (["--premultiply", "--srgb", "--mipmaps"], dict(premultiply=True, srgb=True, mipmaps=True),
     "rgba"),
    (["--alpha-bleed"], dict(alpha_bleed=True), "rgba"),
    (["--alpha-bleed", "--mip-levels", "3"], dict(alpha_bleed=True, mip_levels=3), "rgba"),
    (["--alpha-weighted"], dict(alpha_weighted=True), "rgba"),
    (["--alpha-bleed", "--alpha-weighted", "--mipmaps"],
     dict(alpha_bleed=True, alpha_weighted=True, mipmaps=True), "rgba"),
    (["--normal-map"], dict(normal_map=True), "normal"),
    (["--normal-map", "--mipmaps", "--format", "pvrtc1-2"],
     dict(normal_map=True, mipmaps=True, format="pvrtc1-2"), "normal"),
    (["--mip-levels", "2"], dict(mip_levels=2), "rgb"),
    (["--mipmaps", "--mip-filter", "lanczos"], dict(mipmaps=True, mip_filter="lanczos"), "rgba"),
    (["--mip-levels", "4", "--mip-filter", "kaiser", "--srgb"],
     dict(mip_levels=4, mip_filter="kaiser", srgb=True), "rgb"),
]


def case_image(kind):
    return {"rgba": make_image(64, 32, 4, seed=3), "rgb": make_image(32, 64, 3, seed=4),
            "normal": make_normal_map(64, 64)}[kind]


@pytest.mark.parametrize("flags, keywords, kind", KEYWORD_CASES)
def test_new_keywords_bytes_equal_cli(tmp_path, flags, keywords, kind):
    img = case_image(kind)
    (png,) = write_pngs(tmp_path, [img])
    from_array = tessera.encode(img, **keywords)
    from_file = tessera.encode_file(png, **keywords)
    for ext, zstd in (("pvr", 0), ("ktx", 0), ("ktx2", 0), ("ktx2", 9)):
        cli = cli_bytes(tmp_path, [png], ext, *flags, *(["--zstd", zstd] if zstd else []))
        assert from_array.to_bytes(ext, zstd=zstd) == cli, (ext, zstd)
        assert from_file.to_bytes(ext, zstd=zstd) == cli, (ext, zstd)
    # The keyword does something: without it the texture differs.
    assert from_array != tessera.encode(img, **{k: v for k, v in keywords.items()
                                                if k not in ("flip_y", "premultiply",
                                                             "alpha_bleed", "alpha_weighted",
                                                             "normal_map",
                                                             "mip_levels", "mip_filter")})
    assert from_array.premultiplied == bool(keywords.get("premultiply"))
    if "mip_levels" in keywords:
        assert from_array.level_count == keywords["mip_levels"]


def cube_faces(size=32):
    # Different content per face; face 2 RGB, the others RGBA (one opaque).
    faces = [make_image(size, size, 4, seed=10 + i) for i in range(6)]
    faces[2] = faces[2][..., :3].copy()
    faces[4][..., 3] = 255
    return faces


def test_cube_map_equals_cli(tmp_path):
    faces = cube_faces()
    paths = write_pngs(tmp_path, faces, "face")
    from_list = tessera.encode(faces, cube=True, mipmaps=True, quality="fast")
    rgba = np.stack([f if f.shape[2] == 4 else np.dstack([f, np.full(f.shape[:2], 255, np.uint8)])
                     for f in faces])
    from_axis = tessera.encode(rgba, cube=True, mipmaps=True, quality="fast")
    from_files = tessera.encode_file(paths, cube=True, mipmaps=True, quality="fast")
    assert from_list == from_axis == from_files
    assert (from_list.faces, from_list.layers, from_list.array) == (6, 1, False)
    assert from_list.shape_name == "cube map" and from_list.image_count == 6
    for ext in ("pvr", "ktx", "ktx2"):
        cli = cli_bytes(tmp_path, paths, ext, "--cube", "--mipmaps", "--quality", "fast")
        assert from_list.to_bytes(ext) == cli, ext
    # Tuples work as lists; a leading axis that is a strided view too.
    assert tessera.encode(tuple(faces), cube=True, mipmaps=True, quality="fast") == from_list
    wide = np.concatenate([rgba, rgba], axis=2)[:, :, ::2]
    assert tessera.encode(wide, cube=True, quality="fast") == tessera.encode(
        np.ascontiguousarray(wide), cube=True, quality="fast")


def test_arrays_equal_cli(tmp_path):
    layers = [make_image(16, 32, 3, seed=20 + i) for i in range(3)]
    paths = write_pngs(tmp_path, layers, "layer")
    tex = tessera.encode(np.stack(layers), array=True, format="pvrtc1-2")
    assert tex == tessera.encode(layers, array=True, format="pvrtc1-2")
    assert tex == tessera.encode_file(paths, array=True, format="pvrtc1-2")
    assert (tex.faces, tex.layers, tex.array, tex.shape_name, tex.image_count) == (
        1, 3, True, "array of 3 layers", 3)
    for ext in ("pvr", "ktx2"):
        assert tex.to_bytes(ext) == cli_bytes(tmp_path, paths, ext, "--array", "--format",
                                              "pvrtc1-2")
    # One layer: still an array (KTX says so; PVR v3 cannot).
    one = tessera.encode(np.stack(layers[:1]), array=True)
    assert one.array and one.layers == 1 and one.shape_name == "array of 1 layer"
    assert one.to_bytes("ktx") == cli_bytes(tmp_path, paths[:1], "ktx", "--array")
    assert tessera.from_bytes(one.to_bytes("ktx")) == one
    assert one != tessera.encode(layers[0])  # the same level bytes, another shape
    assert one.levels == tessera.encode(layers[0]).levels


def test_cube_map_arrays_equal_cli(tmp_path):
    faces = [make_image(16, 16, 4, seed=30 + i) for i in range(12)]
    paths = write_pngs(tmp_path, faces, "f")
    stacked = np.stack(faces)
    tex = tessera.encode(stacked.reshape(2, 6, 16, 16, 4), cube=True, array=True, mip_levels=2)
    assert tex == tessera.encode(stacked, cube=True, array=True, mip_levels=2)
    assert tex == tessera.encode(faces, cube=True, array=True, mip_levels=2)
    assert tex == tessera.encode_file(paths, cube=True, array=True, mip_levels=2)
    assert (tex.faces, tex.layers, tex.array, tex.image_count, tex.level_count) == (
        6, 2, True, 12, 2)
    assert tex.shape_name == "cube map array of 2 layers"
    for ext in ("pvr", "ktx", "ktx2"):
        assert tex.to_bytes(ext) == cli_bytes(tmp_path, paths, ext, "--cube", "--array",
                                              "--mip-levels", "2"), ext
    # A cube map and an array of the same six images: the same bytes, not the same texture.
    six = np.stack(faces[:6])
    assert tessera.encode(six, cube=True).levels == tessera.encode(six, array=True).levels
    assert tessera.encode(six, cube=True) != tessera.encode(six, array=True)


def test_cube_arrays_with_new_keywords_equal_cli(tmp_path):
    faces = cube_faces(16)
    paths = write_pngs(tmp_path, faces, "face")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # face 2 has no alpha
        tex = tessera.encode(faces, cube=True, flip_y=True, premultiply=True, mipmaps=True,
                             mip_filter="kaiser")
    assert tex.premultiplied
    assert tex.to_bytes("ktx2", zstd=3) == cli_bytes(
        tmp_path, paths, "ktx2", "--cube", "--flip-y", "--premultiply", "--mipmaps",
        "--mip-filter", "kaiser", "--zstd", "3")


def shaped_textures():
    """One texture of every shape (and flag) the module makes."""
    faces = [make_image(16, 16, 4, seed=40 + i) for i in range(12)]
    rgb = [f[..., :3] for f in faces]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return {
            "2d": tessera.encode(faces[0], mipmaps=True),
            "2d-rgb-srgb": tessera.encode(rgb[0], srgb=True, format="pvrtc1-2"),
            "2d-premultiplied": tessera.encode(faces[1], premultiply=True, mip_levels=3),
            "cube": tessera.encode(faces[:6], cube=True, mipmaps=True),
            "cube-rgb": tessera.encode(rgb[:6], cube=True),
            "array-3": tessera.encode(faces[:3], array=True, mipmaps=True),
            "array-1": tessera.encode(faces[:1], array=True),
            "cube-array-2": tessera.encode(faces, cube=True, array=True, mip_levels=2),
            "cube-array-1": tessera.encode(rgb[:6], cube=True, array=True, srgb=True),
        }


FIELDS = ("format", "width", "height", "has_alpha", "srgb", "premultiplied", "faces", "layers",
          "array", "shape_name", "image_count", "level_count", "levels")


def test_pickling_keeps_every_field_of_every_shape():
    for key, tex in shaped_textures().items():
        for protocol in (2, pickle.HIGHEST_PROTOCOL):
            back = pickle.loads(pickle.dumps(tex, protocol))
            assert back == tex, key
            assert all(getattr(back, f) == getattr(tex, f) for f in FIELDS), key
    # What the pickle keeps beyond the PVR bytes: PVR v3 reads an array of one layer back as a
    # 2D texture.
    one = shaped_textures()["array-1"]
    assert not tessera.from_bytes(one.to_bytes("pvr")).array
    assert pickle.loads(pickle.dumps(one)).array
    # The state of earlier versions (the PVR bytes alone) still loads.
    tex = shaped_textures()["2d"]
    old = tessera.Texture.__new__(tessera.Texture)
    old.__setstate__(tex.to_bytes("pvr"))
    assert old == tex


@pytest.mark.parametrize("zstd", [0, 1, 19, 22])
def test_ktx2_zstd_round_trip(tmp_path, zstd):
    for key, tex in shaped_textures().items():
        data = tex.to_bytes("ktx2", zstd=zstd)
        assert tessera.from_bytes(data) == tex, key
        tex.write(tmp_path / "t.ktx2", zstd=zstd)
        assert (tmp_path / "t.ktx2").read_bytes() == data
        assert tessera.read(tmp_path / "t.ktx2") == tex
        tessera.write(tmp_path / "w.ktx2", tex, zstd=zstd)
        assert (tmp_path / "w.ktx2").read_bytes() == data
    big = shaped_textures()["cube"]
    if zstd:
        assert len(big.to_bytes("ktx2", zstd=zstd)) < len(big.to_bytes("ktx2"))


def test_shape_fields_match_cli_info(tmp_path):
    for key, tex in shaped_textures().items():
        tex.write(tmp_path / "t.ktx2")
        info = json.loads(run_cli("info", tmp_path / "t.ktx2", "--json").stdout)
        assert (tex.shape_name, tex.faces, tex.layers, tex.array, tex.premultiplied) == (
            info["shape"], info["faces"], info["layers"], info["array"], info["premultiplied"]), key
        if key.startswith("2d"):
            assert "2D texture" not in repr(tex) and tex.shape_name == "2D texture"
        else:
            assert f", {tex.shape_name}, " in repr(tex), repr(tex)
    assert "premultiplied" in repr(shaped_textures()["2d-premultiplied"])


def cli_decompress(tmp_path, texture_path, *selection):
    out = tmp_path / "dec.png"
    run_cli("decompress", texture_path, "-o", out, "-q", *selection)
    return tessera.read_image(out)


def test_decode_shapes_and_selection_equal_cli(tmp_path):
    textures = shaped_textures()
    cube = textures["cube"]
    cube.write(tmp_path / "cube.pvr")
    whole = tessera.decode(cube)
    assert whole.shape == (6, 16, 16, 4) and whole.dtype == np.uint8
    for face in range(6):
        expected = cli_decompress(tmp_path, tmp_path / "cube.pvr", "--face", face)
        assert np.array_equal(tessera.decode(cube, face=face), expected), face
        assert np.array_equal(whole[face], expected), face
    assert np.array_equal(tessera.decode(cube, level=2, face=5),
                          cli_decompress(tmp_path, tmp_path / "cube.pvr", "--face", 5, "--level",
                                         2))
    assert tessera.decode(cube, level=2).shape == (6, 4, 4, 4)
    assert tessera.decode(textures["cube-rgb"]).shape == (6, 16, 16, 3)

    array = textures["array-3"]
    array.write(tmp_path / "array.ktx")
    assert tessera.decode(array).shape == (3, 16, 16, 4)
    assert tessera.decode(array, level=1).shape == (3, 8, 8, 4)
    for layer in range(3):
        expected = cli_decompress(tmp_path, tmp_path / "array.ktx", "--layer", layer, "--level", 1)
        assert np.array_equal(tessera.decode(array, level=1, layer=layer), expected)
        assert np.array_equal(tessera.decode(array, level=1)[layer], expected)
    assert tessera.decode(textures["array-1"]).shape == (1, 16, 16, 4)

    # A cube map array, against every image the CLI writes into a folder.
    cubes = textures["cube-array-2"]
    cubes.write(tmp_path / "cubes.ktx2")
    run_cli("decompress", tmp_path / "cubes.ktx2", "-o", f"{tmp_path}/all/", "-q")
    names = ["px", "nx", "py", "ny", "pz", "nz"]
    for level in range(2):
        stack = tessera.decode(cubes, level=level)
        side = 16 >> level
        assert stack.shape == (2, 6, side, side, 4)
        assert tessera.decode(cubes, level=level, layer=1).shape == (6, side, side, 4)
        assert tessera.decode(cubes, level=level, face=3).shape == (2, side, side, 4)
        for layer in range(2):
            for face in range(6):
                png = tmp_path / "all" / f"cubes_layer{layer}_face{face}-{names[face]}" \
                    f"_level{level}.png"
                expected = tessera.read_image(png)
                assert np.array_equal(stack[layer, face], expected)
                assert np.array_equal(tessera.decode(cubes, level=level, layer=layer)[face],
                                      expected)
                assert np.array_equal(tessera.decode(cubes, level=level, face=face)[layer],
                                      expected)
                assert np.array_equal(cubes.decode(level, layer, face, threads=1), expected)
    # A 2D texture: (H, W, C), layer 0 / face 0 name its one image.
    flat = textures["2d"]
    assert np.array_equal(tessera.decode(flat, layer=0, face=0), tessera.decode(flat))
    assert tessera.decode(flat).shape == (16, 16, 4)


@pytest.mark.parametrize("key, kwargs, message", [
    ("cube", dict(face=6), r"^face 6 is out of range \(the cube map has faces 0 to 5\)$"),
    ("cube", dict(face=-1), r"^face -1 is out of range"),
    ("cube", dict(layer=1), r"^layer 1 is out of range \(the texture is not an array: layer 0 "),
    ("array-3", dict(layer=3), r"^layer 3 is out of range \(the array has layers 0 to 2\)$"),
    ("array-3", dict(face=1), r"^face 1 is out of range \(the texture is not a cube map"),
    ("cube-array-2", dict(level=2), r"^level 2 is out of range \(the texture has levels 0 to 1"),
    ("2d", dict(layer=1), r"^layer 1 is out of range"),
])
def test_decode_out_of_range(key, kwargs, message):
    tex = shaped_textures()[key]
    with pytest.raises(tessera.InvalidArgumentError, match=message):
        tessera.decode(tex, **kwargs)
    with pytest.raises(ValueError, match=message):
        tex.decode(**kwargs)


def conflict_cases():
    img = make_image(16, 16, 4)
    six = np.stack([img] * 6)
    return [
        (img, dict(normal_map=True, srgb=True),
         "normal_map and srgb: a normal map holds vectors, never sRGB colour"),
        (img, dict(premultiply=True, alpha_bleed=True),
         r"alpha_bleed and premultiply: bleeding is for straight alpha \(premultiplied "
         r"transparent texels are black already\)"),
        (img, dict(premultiply=True, alpha_weighted=True),
         r"alpha_weighted and premultiply: weighting is for straight alpha \(premultiplied "
         r"colour carries alpha already\)"),
        (img, dict(alpha_weighted=True, format="pvrtc1-2"),
         r"alpha_weighted and format='pvrtc1-2': alpha-weighted colour error is for 4 bpp only"),
        (img, dict(mip_filter="lanczos"),
         "mip_filter='lanczos' needs mipmaps=True or mip_levels=N"),
        (img, dict(mip_filter="gauss", mipmaps=True),
         "mip_filter: 'gauss' is not one of 'box', 'lanczos', 'kaiser'"),
        (img, dict(mip_levels=18), r"mip_levels: 18 is not in \[0, 17\]"),
        (img, dict(mip_levels=-1), r"mip_levels: -1 is not in \[0, 17\]"),
        (img, dict(cube=True), r"<array>: cube=True takes a \(6, H, W, C\) array or a list of 6 "
                               r"\(H, W, C\) arrays, not shape \(16, 16, 4\)"),
        (img, dict(array=True), r"array=True takes an \(L, H, W, C\) array"),
        (six, {}, r"<array>: shape \(6, 16, 16, 4\) holds several images: pass cube=True"),
        ([img, img], {}, r"a list of 2 arrays holds several images: pass cube=True"),
        (six[:5], dict(cube=True), r"not shape \(5, 16, 16, 4\)"),
        (list(six[:5]), dict(cube=True), r"a cube map takes exactly 6 faces \(\+X, -X, \+Y, -Y, "
                                         r"\+Z, -Z\), not 5 \(with array=True: 6 per layer\)"),
        (six[:4], dict(cube=True, array=True), r"cube=True, array=True takes an \(L, 6, H, W, C\) "
                                               r"or \(6L, H, W, C\) array"),
        (six.reshape(2, 3, 16, 16, 4), dict(cube=True, array=True), r"not shape \(2, 3, 16, 16, "),
        (six.reshape(1, 6, 16, 16, 4), dict(array=True), r"array=True takes"),
        ([img] * 6 + [img[:, :, :3]] * 2, dict(cube=True, array=True),
         "a cube map array takes 6 faces per layer: 8 images is not a multiple of 6"),
        ([img, img[:8]], dict(array=True), r"^<array>\[1\]: 16x8, but <array>\[0\] is 16x16 "
                                           r"\(every face and layer needs one size\)$"),
        ([img[:8]] * 6, dict(cube=True, name="sky"), r"^sky\[0\]: 16x8 is not square"),
        ([img, np.zeros((16, 16, 2), np.uint8)], dict(array=True),
         r"^<array>\[1\]: shape \(16, 16, 2\) is not \(H, W, 3\) or \(H, W, 4\)"),
        ([], dict(array=True), "no images to compress"),
    ]


@pytest.mark.parametrize("case", range(len(conflict_cases())))
def test_keyword_errors_name_the_keyword(case):
    x, kwargs, message = conflict_cases()[case]
    with pytest.raises(ValueError, match=message) as info:
        tessera.encode(x, **kwargs)
    assert "--" not in str(info.value).replace("-X", "").replace("-Y", "").replace("-Z", "")


@pytest.mark.parametrize("flags, keywords", [
    (["--normal-map", "--srgb"], dict(normal_map=True, srgb=True)),
    (["--premultiply", "--alpha-bleed"], dict(premultiply=True, alpha_bleed=True)),
    (["--premultiply", "--alpha-weighted"], dict(premultiply=True, alpha_weighted=True)),
])
def test_conflicts_are_the_cli_usage_errors(tmp_path, flags, keywords):
    (png,) = write_pngs(tmp_path, [make_image(16, 16, 4)])
    r = run_cli("compress", png, "-o", tmp_path / "x.pvr", *flags, check=False)
    assert r.returncode == 2
    assert r.stderr.startswith("tessera compress: ")
    cli = r.stderr.strip().removeprefix("tessera compress: ")
    for flag in flags:
        cli = cli.replace(flag, flag[2:].replace("-", "_"))
    for call in (lambda: tessera.encode_file(png, **keywords),
                 lambda: tessera.encode(make_image(16, 16, 4), **keywords)):
        with pytest.raises(ValueError) as info:
            call()
        assert str(info.value) == cli


def test_encode_file_paths_and_shapes(tmp_path):
    paths = write_pngs(tmp_path, [make_image(16, 16, 4, seed=i) for i in range(2)])
    with pytest.raises(ValueError, match=r"img0.png: cube=True takes a list of paths \(6 faces"):
        tessera.encode_file(paths[0], cube=True)
    with pytest.raises(ValueError, match=r"a list of 2 paths needs cube=True .* or array=True"):
        tessera.encode_file(paths)
    with pytest.raises(TypeError, match="expected a path or a list of paths, got int"):
        tessera.encode_file(3)
    with pytest.raises(tessera.Error, match="missing.png"):
        tessera.encode_file([paths[0], tmp_path / "missing.png"], array=True)
    assert tessera.encode_file([str(p) for p in paths], array=True).layers == 2


def test_to_bytes_and_write_keyword_errors(tmp_path):
    tex = tessera.encode(make_image(16, 16, 4))
    with pytest.raises(ValueError, match=r"^zstd needs a KTX 2.0 output \(container='ktx2'\)$"):
        tex.to_bytes("pvr", zstd=3)
    with pytest.raises(ValueError, match=r"^zstd: 23 is not in \[0, 22\]$"):
        tex.to_bytes("ktx2", zstd=23)
    with pytest.raises(ValueError, match=r"^zstd: -1 is not in \[0, 22\]$"):
        tex.to_bytes("ktx2", zstd=-1)
    with pytest.raises(ValueError, match=r"^zstd needs a KTX 2.0 output \(a .ktx2 path\)$"):
        tex.write(tmp_path / "t.ktx", zstd=3)
    with pytest.raises(ValueError, match=r"a .ktx2 path"):
        tessera.write(tmp_path / "t.pvr", tex, zstd=1)
    assert not (tmp_path / "t.ktx").exists() and not (tmp_path / "t.pvr").exists()


def test_premultiply_without_alpha_warns_like_the_cli(tmp_path):
    rgb, rgba = make_image(16, 16, 3), make_image(16, 16, 4)
    (png,) = write_pngs(tmp_path, [rgb])
    r = run_cli("compress", png, "-o", tmp_path / "x.pvr", "--premultiply")
    cli = [line for line in r.stderr.splitlines() if "warning" in line]
    assert cli == [f"tessera: warning: {png} has no alpha channel: --premultiply leaves it as it "
                   "is"]
    with pytest.warns(UserWarning) as record:
        tex = tessera.encode_file(png, premultiply=True)
    assert [str(w.message) for w in record] == [
        cli[0].removeprefix("tessera: warning: ").replace("--premultiply", "premultiply")]
    assert tex.to_bytes() == (tmp_path / "x.pvr").read_bytes() and not tex.premultiplied
    with pytest.warns(UserWarning, match="^<array> has no alpha channel: premultiply leaves it"):
        assert tessera.encode(rgb, premultiply=True) == tessera.encode(rgb)
    with pytest.warns(UserWarning) as record:
        tessera.encode([rgba, rgb, rgba, rgb, rgba, rgba], cube=True, premultiply=True,
                       name="sky")
    assert [str(w.message).split(" ")[0] for w in record] == ["sky[1]", "sky[3]"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert tessera.encode(rgba, premultiply=True).premultiplied  # alpha: no warning
        with pytest.raises(UserWarning):
            tessera.encode(rgb, premultiply=True)
