#!/usr/bin/env python3
"""tessera's engine components on contexts tessera did not make (tests/install/engine_context,
the program the install test also builds against the installed package).

Usage: engine_context_test.py PATH/TO/engine_context_check headless|window [XVFB_RUN]
  headless: the program's own EGL context, with the host loader (eglGetProcAddress) and with no
            loader (first-use resolution from libOpenGL); a gl::Context (the reference); an EGL
            context and a gl::Context alive at once (components on each in turn).
  window:   a GLFW window context (GLX) under Xvfb, with glfwGetProcAddress and with no loader.
Every run must give the reference's image hashes bit for bit (llvmpipe), keep the engine's debug
callback, user pointer and GL state, and answer calls with no current context with one line.
The negative control: --shift (the G-buffer and the face lookups one texel over) changes every
hash, so equal hashes are not vacuous; a "-flat" hash (a one-colour image) fails.
Exits 77 (skipped) without an OpenGL 4.5 context, Xvfb or GLFW, or fails when
TESSERA_TEST_REQUIRE asks for gl / xvfb / glfw (or all).
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_command, skip_or_fail  # noqa: E402

PROG, MODE = sys.argv[1], sys.argv[2]
XVFB = sys.argv[3] if len(sys.argv) > 3 else ""
KEYS = ("adaptive", "reference", "faces")


def run(*args):
    rc, out, err = run_command([PROG, *args], timeout=600)
    if rc == 3:
        what = "glfw" if "GLFW" in err else "gl"
        skip_or_fail(what, f"{' '.join(args)}: {err.strip()}")
    check(f"{args}: exit 0", rc == 0, err)
    try:
        return json.loads(out)
    except json.JSONDecodeError:
        check(f"{args}: JSON", False, out)
        return {"images": {}}


def images_of(r):
    i = r.get("images", {})
    return i if isinstance(i, list) else [i]


def same(label, got, ref):
    for k in KEYS:
        check(f"{label}: {k} hash as on gl::Context", got.get(k) == ref.get(k), (got, ref))
    check(f"{label}: engine state and debug callback kept", got.get("state_error") == "", got)


def no_context(label, r):
    parts = r.get("no_context", "").split("|")
    check(f"{label}: three calls without a context answered", len(parts) == 3, r)
    for p in parts:
        check(f"{label}: one-line 'no current context' error: {p}",
              "no OpenGL context is current on this thread" in p and "\n" not in p, p)


if MODE == "window":
    if not XVFB or not os.environ.get("DISPLAY"):
        skip_or_fail("xvfb", "no xvfb-run (Debian xvfb) for the GLFW window context")

ref = images_of(run("--context", "tessera"))[0]
print(f"gl::Context: {ref}")
for k in KEYS:
    check(f"reference {k}: not a one-colour image", "-flat" not in ref.get(k, "-flat"), ref)
check("adaptive differs from full supersampling", ref.get("adaptive") != ref.get("reference"), ref)
check("gl::Context run keeps its state", ref.get("state_error") == "", ref)

kind = "egl" if MODE == "headless" else "glfw"
for loader in ("host", "none"):
    r = run("--context", kind, "--loader", loader)
    got = images_of(r)[0]
    print(f"{kind} context, loader {loader}: {got}")
    same(f"{kind}/{loader}", got, ref)
    no_context(f"{kind}/{loader}", r)

if MODE == "headless":
    both = images_of(run("--context", "both"))
    check("both: three runs", len(both) == 3, both)
    for n, got in zip(("gl::Context first", "engine context", "gl::Context again"), both):
        same(f"both, {n}", got, ref)

# Negative control: one texel over changes every image.
shifted = images_of(run("--context", kind, "--shift"))[0]
print(f"control, shifted: {shifted}")
for k in KEYS:
    check(f"shifted: {k} hash differs", shifted.get(k) != ref.get(k), (shifted, ref))

sys.exit(finish())
