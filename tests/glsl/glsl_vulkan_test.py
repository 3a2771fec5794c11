#!/usr/bin/env python3
"""Every shipped GLSL file of share/tessera/glsl compiled for Vulkan and for OpenGL 4.5.

Usage: glsl_vulkan_test.py GLSL_DIR [GLSLANGVALIDATOR [SPIRV_VAL [SPIRV_DIS]]]
(a tool given as "" or CMake's ...-NOTFOUND is looked up on PATH).

Each library file (seams, deferred_shading, adaptive_metrics, adaptive_samples, edge_classify,
fxaa) is wrapped as an includer would wrap it (#version 450 core, its macros, #include, a main()
calling every public function; fragment for the derivative-using seams.glsl, compute for all),
then
  * compiled for Vulkan (glslangValidator -V --target-env vulkan1.1, which defines VULKAN) and
    validated (spirv-val --target-env vulkan1.1);
  * its descriptor sets and bindings read back from the SPIR-V (spirv-dis): the documented
    defaults, unique within each set, and moved by every set/binding macro of the file's header;
  * compiled for OpenGL (glslangValidator without -V) with the OpenGL bindings read back from
    glslang's reflection (-q): those the runtime binds, as before.
tessera's own programs (deferred_passes.comp in every pass variant, seams_render.vert/.frag,
deferred_gbuffer.vert/.frag) compile and validate for Vulkan with unique bindings too.
Negative controls: a loose uniform is refused for Vulkan (and accepted by OpenGL), colliding
bindings set through the macros are reported by the uniqueness check, and a truncated SPIR-V
module fails spirv-val.

Without glslangValidator, spirv-val or spirv-dis (Debian: glslang-tools, spirv-tools) the script
exits 77 (skipped), or fails when TESSERA_TEST_REQUIRE names "glslang" or is "all".
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, skip_or_fail  # noqa: E402

GLSL = os.path.abspath(sys.argv[1])
TARGET = "vulkan1.1"


def tool(index, name):
    given = sys.argv[index] if len(sys.argv) > index else ""
    if given and not given.endswith("-NOTFOUND") and os.access(given, os.X_OK):
        return given
    return shutil.which(name)


GLSLANG, SPIRV_VAL, SPIRV_DIS = (tool(2, "glslangValidator"), tool(3, "spirv-val"),
                                 tool(4, "spirv-dis"))
if not (GLSLANG and SPIRV_VAL and SPIRV_DIS):
    missing = [n for n, p in (("glslangValidator", GLSLANG), ("spirv-val", SPIRV_VAL),
                              ("spirv-dis", SPIRV_DIS)) if not p]
    skip_or_fail("glslang", "no " + ", ".join(missing) +
                 " (Debian: glslang-tools, spirv-tools)")

WORK = tempfile.mkdtemp(prefix="tessera_glsl_vulkan_")


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    return p.returncode, (p.stdout + p.stderr).strip()


def last_line(text):
    lines = [line for line in text.splitlines() if line.strip()]
    errors = [line for line in lines if "ERROR" in line or "error" in line]
    return (errors or lines or ["(no output)"])[0]


# --- Wrappers ----------------------------------------------------------------------------------

HEAD = "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n"
# The wrapper's own result buffer, in a set of its own under Vulkan (left out of the checks).
COMP_OUT = """
layout(local_size_x = 64) in;
#if defined(VULKAN)
layout(std430, set = 7, binding = 0) writeonly buffer TesseraTestOut { vec4 tessera_test_out[]; };
#else
layout(std430, binding = 7) writeonly buffer TesseraTestOut { vec4 tessera_test_out[]; };
#endif
"""
WRAPPER_BLOCK = "TesseraTestOut"


def wrapper(include, defines=(), prelude="", body=""):
    return (HEAD + "".join(f"#define {d}\n" for d in defines) + prelude +
            f'#include "{include}"\n' + body)


SEAMS_FRAG = """
layout(location = 0) in vec2 v_uv;
layout(location = 1) flat in int v_face;
layout(location = 0) out vec4 colour;
void main() {
  vec2 dx = dFdx(v_uv), dy = dFdy(v_uv);
  int cls = v_face % TESSERA_SEAMS_CLASSES;
  vec2 uv = tessera_seams_map(v_face % 16, v_uv);
  vec2 gx = tessera_seams_map_gradient(v_face % 16, dx);
  vec4 c = tessera_seams_border_lookup(cls, 1, uv, gx, dy)
         + tessera_seams_clamp_lookup(cls, 2, uv, dx, dy)
         + tessera_seams_face_lookup(v_face, v_uv, dx, dy)
         + tessera_seams_edge_sum(v_face, v_uv, dx, dy);
  c = tessera_seams_resolve(c, v_face, v_uv, dx, dy, false)
    + tessera_seams_sample_clamp(v_face, v_uv, dx, dy)
    + tessera_seams_sample_discard(v_face, v_uv, dx, dy, true)
    + tessera_seams_sample_traverse(v_face, v_uv, dx, dy)
    + tessera_seams_sample_traverse_corners(v_face, v_uv, dx, dy)
    + tessera_seams_sample(v_face % 4, v_face, v_uv, dx, dy);
  colour = c;
}
"""
SEAMS_COMP = COMP_OUT + """
void main() {
  int i = int(gl_GlobalInvocationID.x);
  vec2 uv = vec2(float(i % 8) / 8.0, float(i / 8) / 8.0);
  vec2 dx = vec2(0.01, 0.0), dy = vec2(0.0, 0.01);
  vec4 c = tessera_seams_border_lookup(i % TESSERA_SEAMS_CLASSES, 0,
                                       tessera_seams_map(i % 16, uv), dx, dy)
         + tessera_seams_clamp_lookup(0, 1, uv, tessera_seams_map_gradient(i % 16, dx), dy)
         + tessera_seams_face_lookup(i % 3, uv, dx, dy)
         + tessera_seams_edge_sum(i % 3, uv, dx, dy);
  tessera_test_out[i] = tessera_seams_resolve(c, i % 3, uv, dx, dy, true)
                      + tessera_seams_sample_clamp(i % 3, uv, dx, dy)
                      + tessera_seams_sample_discard(i % 3, uv, dx, dy, false)
                      + tessera_seams_sample_traverse(i % 3, uv, dx, dy)
                      + tessera_seams_sample_traverse_corners(i % 3, uv, dx, dy)
                      + tessera_seams_sample(i % 4, i % 3, uv, dx, dy);
}
"""
SHADING_COMP = COMP_OUT + """
void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  TesseraSample s = tessera_fetch(g);
  vec3 d, p, d2, p2;
  tessera_lighting(g, s, d, p);
  vec3 pos = tessera_position(g, s.depth);
  tessera_blinn_phong(pos, s.normal, tessera_heavy_factor(pos), d2, p2);
  vec4 t = tessera_texture_lod(s.material, vec3(s.uv, 0.0), 0.0)
         + tessera_sample_aniso(0, 1, ivec2(64, 32), s.uv, s.duv);
  vec3 a = tessera_albedo(s, 2.0) + tessera_shade(tessera_window_sample(g, 3), 1.0);
  int id = tessera_fetch_material(g) + tessera_material_id(s.depth);
  tessera_test_out[g.x] = vec4(d + p + d2 + p2 + t.rgb + a, float(id));
}
"""
METRICS_COMP = COMP_OUT + """
void main() {
  int i = int(gl_GlobalInvocationID.x);
  float depths[TESSERA_ADAPTIVE_MAX_N];
  vec3 normals[TESSERA_ADAPTIVE_MAX_N];
  for (int j = 0; j < TESSERA_ADAPTIVE_MAX_N; ++j) {
    depths[j] = 1.0 + float((i + j) % 5);
    normals[j] = vec3(float(j % 3), 1.0, float(i % 2));
  }
  int n = TESSERA_ADAPTIVE_MAX_N;
  float kd = tessera_metric_depth(depths, n, 0.5);
  float kn = tessera_metric_normal(normals, n, 0.5, n);
  float l = tessera_luma_srgb(vec3(kd, kn, 0.5)) + tessera_linear_to_srgb(kd);
  float ks = tessera_metric_shading(l, kd, kn, 0.1, 0.2, 0.05, 0.1, 1.0, n);
  int k = tessera_round_k(max(max(kd, kn), ks), n - 1);
  tessera_test_out[i] = vec4(kd, kn, ks, float(k));
}
"""
SAMPLES_COMP = COMP_OUT + """
void main() {
  int i = int(gl_GlobalInvocationID.x);
  bool seam = tessera_seam_between(vec2(float(i), 0.0) * 0.1, vec4(0.01), vec2(0.3),
                                   vec4(0.02), i % 2, 4.0);
  float s = tessera_scale_uniform(16, i % 16) + tessera_scale_material(16 - i % 8, 1 + i % 4);
  tessera_test_out[i] = vec4(s, seam ? 1.0 : 0.0, 0.0, 1.0);
}
"""
EDGE_COMP = COMP_OUT + """
void main() {
  int i = int(gl_GlobalInvocationID.x);
  vec2 dd = tessera_plane_depth_derivatives(vec3(0.0, 0.0, 1.0), vec3(0.1, 0.2, -1.0),
                                            vec3(0.01, 0.0, 0.0), vec3(0.0, 0.01, 0.0), 2.0);
  float tolerance = tessera_edge_depth_tolerance(2.0, dd, 4, 1.0);
  bool differs = tessera_sample_differs(2.0, vec3(0.0, 0.0, 1.0), tolerance,
                                        2.0 + float(i) * 0.01, vec3(0.1, 0.0, 1.0), 0.99);
  tessera_test_out[i] = vec4(dd, tolerance, differs ? 1.0 : 0.0);
}
"""
FXAA_PRELUDE = """
float tessera_fxaa_luma(ivec2 p) {
  return fract(sin(dot(vec2(p), vec2(12.9898, 78.233))) * 43758.5453);
}
const float tessera_fxaa_p[12] =
    float[12](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);
"""
FXAA_COMP = COMP_OUT + """
void main() {
  int i = int(gl_GlobalInvocationID.x);
  bool early;
  vec2 pos = tessera_fxaa_position(ivec2(i % 8, i / 8), 0.75, 0.125, 0.0312, early);
  tessera_test_out[i] = vec4(pos, tessera_fxaa_luma_bilinear(pos), early ? 1.0 : 0.0);
}
"""

# --- Compilers and readers ---------------------------------------------------------------------

_count = 0


def write(text, stage):
    global _count
    _count += 1
    path = os.path.join(WORK, f"w{_count}.{stage}")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def compile_vulkan(args):
    """glslangValidator -V on `args` (files and options); returns (rc, log, .spv path)."""
    global _count
    _count += 1
    spv = os.path.join(WORK, f"m{_count}.spv")
    rc, out = run([GLSLANG, "-V", "--target-env", TARGET, f"-I{GLSL}", "-o", spv, *args])
    return rc, out, spv


def validate(spv):
    return run([SPIRV_VAL, "--target-env", TARGET, spv])


def spirv_resources(spv):
    """{resource name: (set, binding)} from the SPIR-V's DescriptorSet/Binding decorations, named
    by the variable or, for an anonymous block, by its block type; plus the capability list and
    the storage classes of the module's variables."""
    rc, text = run([SPIRV_DIS, "--raw-id", spv])
    if rc != 0:
        raise RuntimeError("spirv-dis failed: " + text)
    names, deco, defs, caps, classes = {}, {}, {}, [], set()
    for line in text.splitlines():
        line = line.strip()
        m = re.match(r'OpName %(\d+) "(.*)"$', line)
        if m:
            names[m[1]] = m[2]
            continue
        m = re.match(r"OpDecorate %(\d+) (DescriptorSet|Binding) (\d+)$", line)
        if m:
            deco.setdefault(m[1], {})[m[2]] = int(m[3])
            continue
        m = re.match(r"OpCapability (\w+)$", line)
        if m:
            caps.append(m[1])
            continue
        m = re.match(r"%(\d+) = (Op\w+) (.*)$", line)
        if m:
            defs[m[1]] = (m[2], m[3].split())
            if m[2] == "OpVariable":
                classes.add(m[3].split()[1])

    def type_name(tid):
        op, operands = defs.get(tid, ("", []))
        if op == "OpTypePointer":
            return type_name(operands[1].lstrip("%"))
        if op in ("OpTypeArray", "OpTypeRuntimeArray"):
            return type_name(operands[0].lstrip("%"))
        return names.get(tid, "%" + tid)

    resources = {}
    for vid, d in deco.items():
        name = names.get(vid, "")
        if not name:
            name = type_name(defs[vid][1][0].lstrip("%"))
        resources[name] = (d.get("DescriptorSet", 0), d.get("Binding", 0))
    resources.pop(WRAPPER_BLOCK, None)
    return resources, caps, classes


def collisions(resources):
    """[(set, binding, names)] of the bindings that more than one resource uses."""
    used = {}
    for name, sb in resources.items():
        used.setdefault(sb, []).append(name)
    return [(s, b, sorted(n)) for (s, b), n in sorted(used.items()) if len(n) > 1]


def gl_bindings(path):
    """OpenGL compile (glslangValidator, no -V) with reflection: (rc, log, {name: binding}) of the
    samplers and blocks that carry a binding."""
    rc, out = run([GLSLANG, "-l", "-q", f"-I{GLSL}", path])
    bindings = {}
    for line in out.splitlines():
        m = re.match(r"([A-Za-z_]\w*): .*\bbinding (\d+)\b", line)
        if m and m[1] != WRAPPER_BLOCK:
            bindings[m[1]] = int(m[2])
    return rc, out, bindings


def vulkan_check(name, args):
    """Compiles `args` for Vulkan, validates the module and checks that no two resources share a
    set and binding; returns (resources, capabilities, storage classes), resources None when
    the compile failed."""
    rc, out, spv = compile_vulkan(args)
    check(f"{name}: Vulkan compile", rc == 0, last_line(out))
    if rc != 0:
        return None, [], set()
    rc, out = validate(spv)
    check(f"{name}: spirv-val", rc == 0, last_line(out))
    resources, caps, classes = spirv_resources(spv)
    clash = collisions(resources)
    check(f"{name}: bindings unique per set", not clash, f"collisions {clash}")
    return resources, caps, classes


def vulkan_case(name, text, stage):
    """vulkan_check of a wrapper."""
    return vulkan_check(name, [write(text, stage)])


def expect_resources(name, got, want):
    if got is not None:
        check(f"{name}: sets and bindings", got == want, f"got {got}, want {want}")


def gl_case(name, text, stage, want):
    rc, out, bindings = gl_bindings(write(text, stage))
    check(f"{name}: OpenGL compile", rc == 0, last_line(out))
    if rc == 0 and want is not None:
        check(f"{name}: OpenGL bindings", bindings == want, f"got {bindings}, want {want}")


def seams_vk(first, second, third, s=0):
    return {"TesseraSeamsFaces": (s, first), "tessera_seams_border": (s, second),
            "tessera_seams_clamp": (s, third)}


# --- seams.glsl --------------------------------------------------------------------------------

for classes in (1, 4, 16):
    for stage, body in (("frag", SEAMS_FRAG), ("comp", SEAMS_COMP)):
        text = wrapper("seams.glsl", [f"TESSERA_SEAMS_CLASSES {classes}"], body=body)
        name = f"seams.glsl {stage} {classes} classes"
        res, _, _ = vulkan_case(name, text, stage)
        expect_resources(name + " (defaults)", res, seams_vk(0, 1, 2))
        # OpenGL: faces at SSBO 0, units 0 .. N-1 border, N .. 2N-1 clamp (bind(0, 0)).
        gl_case(name, text, stage, {"TesseraSeamsFaces": 0, "tessera_seams_border": 0,
                                    "tessera_seams_clamp": classes})

SEAMS_VARIANTS = [
    ("set 3, first binding 5", ["TESSERA_SEAMS_SET 3", "TESSERA_SEAMS_FIRST_BINDING 5"],
     seams_vk(5, 6, 7, 3)),
    ("each binding", ["TESSERA_SEAMS_SET 1", "TESSERA_SEAMS_FACES_BINDING 9",
                      "TESSERA_SEAMS_BORDER_BINDING 4", "TESSERA_SEAMS_CLAMP_BINDING 2"],
     seams_vk(9, 4, 2, 1)),
    ("first binding 3, faces 0", ["TESSERA_SEAMS_FIRST_BINDING 3",
                                  "TESSERA_SEAMS_FACES_BINDING 0"], seams_vk(0, 4, 5)),
    ("OpenGL's first unit ignored", ["TESSERA_SEAMS_FIRST_UNIT 9"], seams_vk(0, 1, 2)),
]
for label, defines, want in SEAMS_VARIANTS:
    text = wrapper("seams.glsl", ["TESSERA_SEAMS_CLASSES 3", *defines], body=SEAMS_FRAG)
    res, _, _ = vulkan_case(f"seams.glsl {label}", text, "frag")
    expect_resources(f"seams.glsl {label}", res, want)
# OpenGL keeps its own macros: bind(2, 3) with 3 classes.
gl_case("seams.glsl OpenGL first unit 2, faces 3",
        wrapper("seams.glsl", ["TESSERA_SEAMS_CLASSES 3", "TESSERA_SEAMS_FIRST_UNIT 2",
                               "TESSERA_SEAMS_FACES_BINDING 3"], body=SEAMS_FRAG), "frag",
        {"TesseraSeamsFaces": 3, "tessera_seams_border": 2, "tessera_seams_clamp": 5})

# --- deferred_shading.glsl ---------------------------------------------------------------------

SHADING_NAMES = ["TesseraDeferredParams", "TesseraLights", "TesseraMaterials", "TesseraWaves",
                 "tessera_gbuffer0", "tessera_gbuffer1", "tessera_gbuffer2", "tessera_textures"]
SHADING_MACROS = ["PARAMS", "LIGHTS", "MATERIALS", "WAVES", "GBUFFER0", "GBUFFER1", "GBUFFER2",
                  "TEXTURES"]
for classes in (1, 8):
    text = wrapper("deferred_shading.glsl", [f"TESSERA_DEFERRED_CLASSES {classes}"],
                   body=SHADING_COMP)
    name = f"deferred_shading.glsl comp {classes} classes"
    res, _, _ = vulkan_case(name, text, "comp")
    expect_resources(name + " (defaults)", res,
                     {n: (0, b) for b, n in enumerate(SHADING_NAMES)})
    # OpenGL: UBO 0, SSBOs 0-2, units 0-2 and 3 .. 3+C-1 (DeferredRenderer).
    gl_case(name, text, "comp", {"TesseraDeferredParams": 0, "TesseraLights": 0,
                                 "TesseraMaterials": 1, "TesseraWaves": 2,
                                 "tessera_gbuffer0": 0, "tessera_gbuffer1": 1,
                                 "tessera_gbuffer2": 2, "tessera_textures": 3})
SHADING_VARIANTS = [
    ("set 2, first binding 10", ["TESSERA_DEFERRED_SET 2", "TESSERA_DEFERRED_FIRST_BINDING 10"],
     {n: (2, 10 + b) for b, n in enumerate(SHADING_NAMES)}),
    ("each binding, reversed",
     ["TESSERA_DEFERRED_SET 4"] +
     [f"TESSERA_DEFERRED_{m}_BINDING {20 - b}" for b, m in enumerate(SHADING_MACROS)],
     {n: (4, 20 - b) for b, n in enumerate(SHADING_NAMES)}),
]
for label, defines, want in SHADING_VARIANTS:
    text = wrapper("deferred_shading.glsl", ["TESSERA_DEFERRED_CLASSES 2", *defines],
                   body=SHADING_COMP)
    res, _, _ = vulkan_case(f"deferred_shading.glsl {label}", text, "comp")
    expect_resources(f"deferred_shading.glsl {label}", res, want)

# --- The pure files: no resources of their own -------------------------------------------------

PURE = [
    ("adaptive_metrics.glsl", [], "", METRICS_COMP),
    ("adaptive_metrics.glsl", ["TESSERA_ADAPTIVE_MAX_N 16"], "", METRICS_COMP),
    ("adaptive_metrics.glsl", ["TESSERA_ADAPTIVE_NO_FP64 1"], "", METRICS_COMP),
    ("adaptive_samples.glsl", [], "", SAMPLES_COMP),
    ("edge_classify.glsl", [], "", EDGE_COMP),
    ("fxaa.glsl", ["TESSERA_FXAA_STEPS 12"], FXAA_PRELUDE, FXAA_COMP),
    ("fxaa.glsl", ["TESSERA_FXAA_STEPS 3"], FXAA_PRELUDE, FXAA_COMP),
]
for include, defines, prelude, body in PURE:
    text = wrapper(include, defines, prelude, body)
    name = f"{include} comp {' '.join(defines)}".strip()
    res, caps, _ = vulkan_case(name, text, "comp")
    expect_resources(name + " (no bindings)", res, {})
    if include == "adaptive_metrics.glsl" and res is not None:
        no_fp64 = "TESSERA_ADAPTIVE_NO_FP64 1" in defines
        check(f"{name}: Float64 capability {'absent' if no_fp64 else 'present'} (documented)",
              ("Float64" in caps) != no_fp64, f"caps {caps}")
    gl_case(name, text, "comp", {})

# --- tessera's own programs --------------------------------------------------------------------

FXAA_DEFINES = ["-DTESSERA_FXAA_STEPS=12",
                "-DTESSERA_FXAA_P=float[12](1.0,1.0,1.0,1.0,1.0,1.5,2.0,2.0,2.0,2.0,4.0,8.0)",
                "-DTESSERA_FXAA_SUBPIX=0.75", "-DTESSERA_FXAA_EDGE=0.125",
                "-DTESSERA_FXAA_EDGE_MIN=0.0312"]
PASSES = {  # the variants tests/glsl/CMakeLists.txt checks for OpenGL
    "first": ["-DTESSERA_PASS_FIRST"], "metrics": ["-DTESSERA_PASS_METRICS"],
    "reference": ["-DTESSERA_PASS_REFERENCE"],
    "srgb8": ["-DTESSERA_PASS_SRGB8", "-DTESSERA_SRGB_FROM_S"],
    "extra_tile": ["-DTESSERA_PASS_EXTRA"],
    "extra_loop": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_SCHEDULE_LOOP"],
    "edge": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_EDGE"],
    "frame_list": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_SCHEDULE_FRAME", "-DTESSERA_FRAME_LIST"],
    "frame_shade": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_SCHEDULE_FRAME", "-DTESSERA_FRAME_SHADE"],
    "frame_resolve": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_SCHEDULE_FRAME",
                      "-DTESSERA_FRAME_RESOLVE"],
    "edge_frame_list": ["-DTESSERA_PASS_EXTRA", "-DTESSERA_EDGE", "-DTESSERA_SCHEDULE_FRAME",
                        "-DTESSERA_FRAME_LIST"],
    "fxaa": ["-DTESSERA_PASS_FXAA", *FXAA_DEFINES],
}
PASS_COMMON = ["-DTESSERA_GLSLANG", "-DTESSERA_DEFERRED_CLASSES=3", "-DTESSERA_WINDOW_N=16",
               "-DTESSERA_ADAPTIVE_MAX_N=16", "-S", "comp"]
PASSES_FILE = os.path.join(GLSL, "deferred_passes.comp")


for variant, defines in PASSES.items():
    res, _, _ = vulkan_check(f"deferred_passes.comp {variant}",
                             [*PASS_COMMON, *defines, PASSES_FILE])
    if res is not None and variant == "frame_list":
        # deferred_shading.glsl's 0..7, then OpenGL's SSBO k at 8 + k - 3.
        want = {n: (0, b) for b, n in enumerate(SHADING_NAMES)}
        want.update({"TesseraS": (0, 8), "TesseraTerms": (0, 9), "TesseraK": (0, 10),
                     "TesseraOut": (0, 11), "TesseraRgba8": (0, 12), "TesseraRgba8Out": (0, 13),
                     "TesseraListBase": (0, 14), "TesseraListItems": (0, 15),
                     "TesseraListColours": (0, 16)})
        check("deferred_passes.comp frame_list: default sets and bindings", res == want,
              f"got {res}")
# A pass macro that names no pass (renamed or misspelt) is a compile error, not an empty main.
rc, out, _ = compile_vulkan([*PASS_COMMON, "-DTESSERA_PASS_FRIST", PASSES_FILE])
check("deferred_passes.comp with an unknown pass: a compile error",
      rc != 0 and "no known TESSERA_PASS_" in out, last_line(out))
res, _, _ = vulkan_check("deferred_passes.comp frame_list, set 2, first binding 4",
                         [*PASS_COMMON, *PASSES["frame_list"], "-DTESSERA_DEFERRED_SET=2",
                          "-DTESSERA_DEFERRED_FIRST_BINDING=4", PASSES_FILE])
if res is not None:
    check("deferred_passes.comp moved: all in set 2, from binding 4",
          {s for s, _ in res.values()} == {2} and min(b for _, b in res.values()) == 4 and
          res.get("TesseraListColours") == (2, 20), f"got {res}")

RENDER = [(4, 0, 1, 0), (4, 0, 1, 1), (4, 1, 1, 0), (4, 1, 0, 1), (4, 2, 1, 0), (4, 3, 1, 1),
          (1, 2, 1, 0), (16, 3, 1, 0)]
for classes, method, fallback, output in RENDER:
    name = (f"seams_render.frag {classes} classes method {method} fallback {fallback}"
            f" output {output}")
    res, _, classes_used = vulkan_check(name, [
        "-DTESSERA_GLSLANG", f"-DTESSERA_SEAMS_CLASSES={classes}",
        f"-DTESSERA_RENDER_METHOD={method}", f"-DTESSERA_RENDER_FALLBACK={fallback}",
        f"-DTESSERA_RENDER_OUTPUT={output}", os.path.join(GLSL, "seams_render.frag")])
    if res is not None:
        check(f"{name}: seams.glsl defaults, class as push constant",
              res == seams_vk(0, 1, 2) and "PushConstant" in classes_used, f"got {res}")
# Devices without shaderSampledImageArrayDynamicIndexing (lavapipe): the class as specialization
# constant 0 (src/vk/face_renderer.h), the same resources, no push constant.
for method in (1, 3):
    name = f"seams_render.frag 4 classes method {method}, class constant"
    res, _, classes_used = vulkan_check(name, [
        "-DTESSERA_GLSLANG", "-DTESSERA_SEAMS_CLASSES=4", f"-DTESSERA_RENDER_METHOD={method}",
        "-DTESSERA_RENDER_CLASS_CONSTANT=1", os.path.join(GLSL, "seams_render.frag")])
    if res is not None:
        check(f"{name}: seams.glsl defaults, no push constant",
              res == seams_vk(0, 1, 2) and "PushConstant" not in classes_used, f"got {res}")
for stage in ("seams_render.vert", "deferred_gbuffer.vert", "deferred_gbuffer.frag"):
    res, _, classes_used = vulkan_check(stage, [os.path.join(GLSL, stage)])
    if res is not None:
        check(f"{stage}: no descriptors", res == {}, f"got {res}")
        if stage.endswith(".frag"):
            check(f"{stage}: material id as push constant", "PushConstant" in classes_used,
                  f"storage classes {sorted(classes_used)}")

# --- Negative controls -------------------------------------------------------------------------

# A loose (non-opaque, outside a block) uniform: OpenGL takes it, Vulkan must refuse it.
loose = wrapper("seams.glsl", ["TESSERA_SEAMS_CLASSES 2"], "uniform float tessera_test_loose;\n",
                SEAMS_FRAG.replace("colour = c;", "colour = c * tessera_test_loose;"))
rc, out, _ = compile_vulkan([write(loose, "frag")])
check("negative: loose uniform refused for Vulkan",
      rc != 0 and "non-opaque uniforms outside a block" in out, last_line(out))
rc, out, _ = gl_bindings(write(loose, "frag"))
check("negative: the same loose uniform compiles for OpenGL", rc == 0, last_line(out))

# Colliding bindings through the macros compile and validate; the uniqueness check catches them.
clash_text = wrapper("seams.glsl", ["TESSERA_SEAMS_CLASSES 2", "TESSERA_SEAMS_BORDER_BINDING 0"],
                     body=SEAMS_FRAG)
rc, out, spv = compile_vulkan([write(clash_text, "frag")])
check("negative: colliding bindings still compile", rc == 0, last_line(out))
if rc == 0:
    found = collisions(spirv_resources(spv)[0])
    check("negative: colliding bindings detected",
          found == [(0, 0, ["TesseraSeamsFaces", "tessera_seams_border"])], f"found {found}")

# spirv-val is live: a truncated module fails it.
rc, out, spv = compile_vulkan([write(wrapper("edge_classify.glsl", body=EDGE_COMP), "comp")])
if rc == 0:
    with open(spv, "rb") as f:
        data = f.read()
    bad = spv + ".truncated.spv"
    with open(bad, "wb") as f:
        f.write(data[: len(data) // 2 // 4 * 4])
    rc, out = validate(bad)
    check("negative: truncated SPIR-V fails spirv-val", rc != 0, last_line(out))
else:
    check("negative: truncated SPIR-V fails spirv-val", False, "edge_classify.glsl: " + out)

shutil.rmtree(WORK, ignore_errors=True)
sys.exit(finish())
