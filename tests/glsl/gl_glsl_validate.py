#!/usr/bin/env python3
"""Runs glslangValidator (the Khronos reference compiler) over share/tessera/glsl/seams.glsl.

Usage: gl_glsl_validate.py PATH/TO/glslangValidator PATH/TO/seams.glsl
The file is wrapped the way a user includes it (#version 450 core, TESSERA_SEAMS_CLASSES, a
main() calling every method) for 1, 4 and 16 classes in a fragment shader (implicit dFdx/dFdy
gradients) and a compute shader; and it must refuse to compile without TESSERA_SEAMS_CLASSES
or with 17 classes, naming the macro.
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check as harness_check, finish  # noqa: E402

VALIDATOR, SEAMS = sys.argv[1], sys.argv[2]
source = open(SEAMS, encoding="utf-8").read()

FRAG_MAIN = """
layout(location = 0) in vec2 v_uv;
layout(location = 1) flat in int v_face;
layout(location = 0) out vec4 colour;
void main() {
  vec2 dx = dFdx(v_uv), dy = dFdy(v_uv);
  vec4 c = tessera_seams_sample_clamp(v_face, v_uv, dx, dy)
         + tessera_seams_sample_discard(v_face, v_uv, dx, dy, true)
         + tessera_seams_sample_traverse(v_face, v_uv, dx, dy)
         + tessera_seams_sample_traverse_corners(v_face, v_uv, dx, dy)
         + tessera_seams_sample(1, v_face, v_uv, dx, dy);
  colour = vec4(c.rgb, 1.0);
}
"""
COMP_MAIN = """
layout(local_size_x = 64) in;
layout(std430, binding = 1) writeonly buffer Out { vec4 result[]; };
void main() {
  int i = int(gl_GlobalInvocationID.x);
  vec2 uv = vec2(float(i % 8) / 8.0, float(i / 8) / 8.0);
  result[i] = tessera_seams_sample(i % 4, i % 3, uv, vec2(0.01, 0.0), vec2(0.0, 0.01));
}
"""


def check(name, cond, detail):
    """cli_harness.check, printing the passed checks too (their detail is the measurement)."""
    harness_check(name, cond, detail, show_passed=True)


def validate(stage, defines, main):
    text = "#version 450 core\n" + "".join(f"#define {d}\n" for d in defines)
    text += "#line 1\n" + source + main
    with tempfile.NamedTemporaryFile("w", suffix="." + stage, delete=False) as f:
        f.write(text)
        path = f.name
    try:
        p = subprocess.run([VALIDATOR, path], capture_output=True, text=True)
        return p.returncode, (p.stdout + p.stderr).strip()
    finally:
        os.unlink(path)


for classes in (1, 4, 16):
    for stage, main in (("frag", FRAG_MAIN), ("comp", COMP_MAIN)):
        rc, out = validate(stage, [f"TESSERA_SEAMS_CLASSES {classes}"], main)
        check(f"{stage} with {classes} classes", rc == 0, out.splitlines()[-1] if out else "ok")
rc, out = validate("frag", ["TESSERA_SEAMS_FIRST_UNIT 2", "TESSERA_SEAMS_FACES_BINDING 3",
                            "TESSERA_SEAMS_CLASSES 3"], FRAG_MAIN)
check("custom unit and binding", rc == 0, out.splitlines()[-1] if out else "ok")
rc, out = validate("frag", [], FRAG_MAIN)
check("refused without TESSERA_SEAMS_CLASSES", rc != 0 and "TESSERA_SEAMS_CLASSES" in out,
      out.splitlines()[1] if len(out.splitlines()) > 1 else out)
rc, out = validate("frag", ["TESSERA_SEAMS_CLASSES 17"], FRAG_MAIN)
check("refused with 17 classes", rc != 0 and "1..16" in out,
      out.splitlines()[1] if len(out.splitlines()) > 1 else out)

sys.exit(finish())
