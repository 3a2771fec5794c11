#!/usr/bin/env python3
"""KTX 2.0 files tessera writes, read by an independent parser (ktx-parse, npm).

Usage: ktx2_oracle_test.py PATH/TO/ktx2_oracle_writer PATH/TO/ktx2_oracle.mjs KTX_PARSE_DIR VERSION
  * ktx2_oracle_writer writes every variant of tests/support/ktx2_test_util.h (real PVRTC encodes:
    4/2 bpp, sRGB and linear, premultiplied, mips, cube map, arrays of 3 and 1, cube map arrays, no
    zstd / zstd 3 / zstd 19, opaque and with alpha) and a manifest of what each texture holds, after
    checking that tessera reads each file back identical;
  * ktx2_oracle.mjs reads every file with ktx-parse (fzstd inflates zstd levels);
  * every header field, the whole Data Format Descriptor, the key/value data and each level's
    bytes (sha256) and uncompressedByteLength must be what the manifest says, stated here from
    the KTX 2.0 and Khronos Data Format specifications, not from tessera's code; so must the
    layout (index, DFD, key/value data, then levels smallest first, 8-byte aligned unless
    supercompressed, level 0 ending the file).
Negative controls: a deliberately wrong expectation, and files with one byte changed (a level's
data, the DFD's transfer function, a zstd frame), must each be reported as a difference.
KTX_PARSE_DIR (empty: $TESSERA_KTX_PARSE, else the setup cache) holds node_modules/ktx-parse and
node_modules/fzstd. Exits 77 (CTest: skipped) without node or those packages.
"""
import copy
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_command, skip_or_fail  # noqa: E402

WRITER, ORACLE, KTX_PARSE, VERSION = sys.argv[1:5]

VK_FORMATS = {("4bpp", False): 1000054001, ("4bpp", True): 1000054005,
              ("2bpp", False): 1000054000, ("2bpp", True): 1000054004}


def ktx_parse_dir():
    d = KTX_PARSE or os.environ.get("TESSERA_KTX_PARSE", "")
    if not d:
        cache = os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache"))
        d = os.path.join(cache, "tessera", "peers", "ktx-parse")
    return d


def expected(m):
    """What a KTX 2.0 reader must find in the file written for manifest entry `m`."""
    four = m["format"] == "4bpp"
    return {
        "vkFormat": VK_FORMATS[(m["format"], m["srgb"])],
        "typeSize": 1,
        "pixelWidth": m["width"],
        "pixelHeight": m["height"],
        "pixelDepth": 0,
        "layerCount": m["layers"] if m["array"] else 0,
        "faceCount": m["faces"],
        "levelCount": len(m["levels"]),
        "supercompressionScheme": 2 if m["zstd_level"] else 0,
        "index.dfdByteLength": 44,
        "index.sgdByteOffset": 0,
        "index.sgdByteLength": 0,
        "dfd": {
            "vendorId": 0, "descriptorType": 0, "versionNumber": 2,
            "colorModel": 164,  # KHR_DF_MODEL_PVRTC
            "colorPrimaries": 1,  # BT709
            "transferFunction": 2 if m["srgb"] else 1,  # SRGB or LINEAR
            "flags": 1 if m["premultiplied"] else 0,  # ALPHA_PREMULTIPLIED
            "texelBlockDimension": [3, 3, 0, 0] if four else [7, 3, 0, 0],
            "bytesPlane": [8, 0, 0, 0, 0, 0, 0, 0],
            "samples": [{"bitOffset": 0, "bitLength": 63, "channelType": 0,
                         "samplePosition": [0, 0, 0, 0], "sampleLower": 0,
                         "sampleUpper": 0xFFFFFFFF}],
        },
        "keyValue": {"KTXorientation": "rd", "KTXwriter": "tessera " + VERSION},
        "levels": [{"uncompressedByteLength": len(h) // 2, "decompressedLength": len(h) // 2,
                    "sha256": hashlib.sha256(bytes.fromhex(h)).hexdigest()}
                   for h in m["levels"]],
    }


def layout_problems(o):
    """Where the parts of file `o` (as the oracle saw it) are not where KTX 2.0 puts them."""
    problems = []
    idx = o["index"]
    n = o["levelCount"]
    if idx["dfdByteOffset"] != 80 + 24 * n:
        problems.append(f"dfdByteOffset {idx['dfdByteOffset']} is not right after the index")
    if idx["kvdByteOffset"] != idx["dfdByteOffset"] + idx["dfdByteLength"]:
        problems.append("the key/value data does not follow the DFD")
    align = 1 if o["supercompressionScheme"] else 8
    end = idx["kvdByteOffset"] + idx["kvdByteLength"]
    for i in reversed(range(n)):  # stored smallest level first
        lv = o["levels"][i]
        start = -(-end // align) * align
        if lv["byteOffset"] != start:
            problems.append(f"level {i} at byte {lv['byteOffset']}, expected {start}")
        if not o["supercompressionScheme"] and lv["byteLength"] != lv["uncompressedByteLength"]:
            problems.append(f"level {i} byteLength differs from uncompressedByteLength")
        end = lv["byteOffset"] + lv["byteLength"]
    if end != o["fileSize"]:
        problems.append(f"level 0 ends at byte {end}, the file at {o['fileSize']}")
    return problems


def differences(want, got):
    """Every field where the oracle's reading `got` differs from `want`, as text."""
    if "error" in got:
        return [f"ktx-parse failed: {got['error']}"]
    diffs = []
    for key, value in want.items():
        if key == "levels":
            if len(got["levels"]) != len(value):
                diffs.append(f"{len(got['levels'])} levels, expected {len(value)}")
                continue
            for i, (w, g) in enumerate(zip(value, got["levels"])):
                for k, v in w.items():
                    if g[k] != v:
                        diffs.append(f"level {i} {k}: {g[k]} != {v}")
            continue
        have = got["index"][key[6:]] if key.startswith("index.") else got[key]
        if key in ("dfd", "keyValue"):
            for k, v in value.items():
                if have.get(k) != v:
                    diffs.append(f"{key}.{k}: {have.get(k)!r} != {v!r}")
            for k in set(have) - set(value):
                diffs.append(f"{key}.{k}: unexpected {have[k]!r}")
        elif have != value:
            diffs.append(f"{key}: {have!r} != {value!r}")
    return diffs + layout_problems(got)


def read_with_oracle(files):
    rc, out, err = run_command(["node", ORACLE, ktx_parse_dir(), *files])
    check("oracle ran", rc == 0, f"rc={rc} stderr={err!r}")
    return json.loads(out) if rc == 0 else [{"file": f, "error": err} for f in files]


def main():
    modules = os.path.join(ktx_parse_dir(), "node_modules")
    if shutil.which("node") is None:
        skip_or_fail("ktx-parse", "node is not installed (scripts/setup.sh installs it)")
    for package in ("ktx-parse", "fzstd"):
        if not os.path.isfile(os.path.join(modules, package, "package.json")):
            skip_or_fail("ktx-parse", f"{package} not found in {modules} (scripts/setup.sh installs it)")
    with tempfile.TemporaryDirectory() as tmp:
        rc, _, err = run_command([WRITER, tmp])
        check("tessera writes every variant and reads it back identical", rc == 0, err)
        if rc != 0:
            return finish()
        with open(os.path.join(tmp, "manifest.json")) as f:
            manifest = json.load(f)
        got = read_with_oracle([m["file"] for m in manifest])
        check("one reading per file", len(got) == len(manifest), f"{len(got)} readings")
        for m, g in zip(manifest, got):
            diffs = differences(expected(m), g)
            check(m["name"], not diffs, "; ".join(diffs))
        shapes = {(m["faces"], m["array"], m["zstd_level"] > 0, m["has_alpha"]) for m in manifest}
        check("variants cover cube arrays with zstd and alpha", (6, True, True, True) in shapes)

        # Negative controls: the comparison must see a wrong expectation ...
        m0, g0 = manifest[0], got[0]
        wrong = copy.deepcopy(expected(m0))
        wrong["dfd"]["transferFunction"] = 3 - wrong["dfd"]["transferFunction"]
        diffs = differences(wrong, g0)
        check("negative control: a wrong expectation is reported",
              any("transferFunction" in d for d in diffs), f"{diffs}")
        # ... and files changed in one byte (level 0's last byte, the DFD's transfer function,
        # the middle of a zstd level), read by the oracle itself.
        plain = next(m for m in manifest if not m["zstd_level"])
        packed = next(m for m in manifest if m["zstd_level"])
        tampered = []
        for m, where in ((plain, "level"), (plain, "dfd"), (packed, "zstd")):
            with open(m["file"], "rb") as f:
                data = bytearray(f.read())
            dfd_at = int.from_bytes(data[48:52], "little")
            at = {"level": len(data) - 1, "dfd": dfd_at + 14, "zstd": len(data) - 8}[where]
            data[at] ^= 0x03 if where == "dfd" else 0x55  # transfer 1 <-> 2
            path = os.path.join(tmp, f"tampered-{where}.ktx2")
            with open(path, "wb") as f:
                f.write(data)
            tampered.append((m, where, path))
        readings = read_with_oracle([p for _, _, p in tampered])
        for (m, where, _), g in zip(tampered, readings):
            diffs = differences(expected(m), g)
            wanted = {"level": "level 0 sha256", "dfd": "dfd.transferFunction",
                      "zstd": ""}[where]
            check(f"negative control: a changed {where} byte is reported",
                  bool(diffs) and any(wanted in d for d in diffs), f"{diffs}")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
