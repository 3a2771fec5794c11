#!/usr/bin/env python3
"""CLI tests of where bytes go: `-` for stdin and stdout, pipes and process substitution as
inputs, and outputs that are symbolic links, dangling links, FIFOs, devices, read-only folders or
terminals. Writes must never replace what is not the user's file.

Usage: cli_io_test.py PATH/TO/tessera
"""
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import threading

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_on_pty  # noqa: E402

TESSERA = os.path.abspath(sys.argv[1])


def run(args, stdin=None, shell=False):
    """Runs tessera with bytes on stdin; returns (rc, stdout bytes, stderr text)."""
    cmd = args if shell else [TESSERA, *args]
    p = subprocess.run(cmd, input=stdin, capture_output=True, timeout=120, shell=shell,
                       executable="/bin/bash" if shell else None)
    return p.returncode, p.stdout, p.stderr.decode(errors="replace")


def read(path):
    with open(path, "rb") as f:
        return f.read()


tmp = tempfile.mkdtemp(prefix="tessera-io-")
os.chmod(tmp, 0o755)
try:
    rc, _, err = run(["demo", "-o", os.path.join(tmp, "d"), "--size", "64"])
    check("demo for inputs", rc == 0, err)
    png = os.path.join(tmp, "in.png")
    shutil.copy(os.path.join(tmp, "d", "img", "images-foliage.png"), png)
    ref_pvr, ref_ktx = os.path.join(tmp, "ref.pvr"), os.path.join(tmp, "ref.ktx")
    check("compress to file", run(["compress", png, "-o", ref_pvr, "-q"])[0] == 0)
    check("compress to ktx", run(["compress", png, "-o", ref_ktx, "-q"])[0] == 0)
    ref_png = os.path.join(tmp, "ref-dec.png")
    check("decompress to file", run(["decompress", ref_pvr, "-o", ref_png, "-q"])[0] == 0)

    # --- stdout -------------------------------------------------------------------------------
    rc, out, err = run(["compress", png, "-o", "-"])
    check("compress -o - equals the file", rc == 0 and out == read(ref_pvr), err)
    check("compress -o -: summary on stderr", "wrote <stdout>" in err, err)
    rc, out, err = run(["compress", png, "-o", "-", "--container", "ktx", "-q"])
    check("compress -o - --container ktx equals the .ktx file", rc == 0 and out == read(ref_ktx),
          err)
    rc, out, err = run(["decompress", ref_pvr, "-o", "-"])
    check("decompress -o - equals the file", rc == 0 and out == read(ref_png), err)
    heat = os.path.join(tmp, "heat.png")
    run(["compare", png, ref_png, "--heatmap", heat])
    rc, out, err = run(["compare", png, ref_png, "--heatmap", "-", "--json"])
    check("compare --heatmap - equals the file", rc == 0 and out == read(heat), err)
    check("compare --heatmap -: results on stderr", '"psnr_rgb"' in err, err)

    # --- stdin, pipes, /dev/stdin, process substitution ----------------------------------------
    rc, out, err = run(["compress", "-", "-o", "-", "-q"], stdin=read(png))
    check("cat a.png | compress - equals the file", rc == 0 and out == read(ref_pvr), err)
    rc, out, err = run(f"cat {png} | {TESSERA} compress /dev/stdin -o - -q", shell=True)
    check("compress /dev/stdin from a pipe", rc == 0 and out == read(ref_pvr), err)
    rc, out, err = run(f"{TESSERA} compress <(cat {png}) -o - -q", shell=True)
    check("compress <(process substitution)", rc == 0 and out == read(ref_pvr), err)
    rc, out, err = run(["decompress", "-", "-o", "-"], stdin=read(ref_ktx))
    check("decompress - (KTX by its magic)", rc == 0 and out == read(ref_png), err)
    rc, out, err = run(["info", "-", "--json"], stdin=read(ref_pvr))
    check("info -", rc == 0 and b'"file": "<stdin>"' in out, err)
    rc, out, err = run(["compare", "-", ref_png, "--json"], stdin=read(png))
    check("compare - B", rc == 0 and b'"psnr_rgb"' in out, err)
    # Formats come from the bytes, not the name.
    disguised = os.path.join(tmp, "texture.png")
    shutil.copy(ref_pvr, disguised)
    rc, out, err = run(["decompress", disguised, "-o", "-"])
    check("a .pvr named .png decodes by its magic", rc == 0 and out == read(ref_png), err)
    rc, out, err = run(["compress", "-", "-o", os.path.join(tmp, "x.pvr")], stdin=b"")
    check("empty stdin is bad input", rc == 1 and "<stdin>" in err and err.count("\n") == 1, err)
    check("empty stdin leaves no output", not os.path.exists(os.path.join(tmp, "x.pvr")))
    rc, out, err = run(["compress", "-", "-o", "-"], stdin=read(png)[:100])
    check("truncated stdin is bad input", rc == 1 and "<stdin>" in err and not out, err)

    # --- outputs that are not plain files -----------------------------------------------------
    os.makedirs(os.path.join(tmp, "real"))
    target = os.path.join(tmp, "real", "target.pvr")
    with open(target, "wb") as f:
        f.write(b"old")
    link = os.path.join(tmp, "link.pvr")
    os.symlink("real/target.pvr", link)
    rc, _, err = run(["compress", png, "-o", link, "-q"])
    check("symlink: written through", rc == 0 and read(target) == read(ref_pvr), err)
    check("symlink: still a link", os.path.islink(link) and os.readlink(link) == "real/target.pvr")
    dangling = os.path.join(tmp, "dangling.png")
    os.symlink("real/made.png", dangling)
    rc, _, err = run(["decompress", ref_pvr, "-o", dangling, "-q"])
    check("dangling link: target created",
          rc == 0 and read(os.path.join(tmp, "real", "made.png")) == read(ref_png), err)
    check("dangling link: still a link", os.path.islink(dangling))

    fifo = os.path.join(tmp, "pipe")
    os.mkfifo(fifo)
    got = {}

    def reader():
        got["bytes"] = read(fifo)

    t = threading.Thread(target=reader)
    t.start()
    rc, _, err = run(["compress", png, "-o", fifo, "--container", "pvr", "-q"])
    t.join(60)
    check("FIFO with a reader gets the bytes", rc == 0 and got.get("bytes") == read(ref_pvr), err)
    check("FIFO is still a FIFO", stat.S_ISFIFO(os.lstat(fifo).st_mode))

    rc, _, err = run(["decompress", ref_pvr, "-o", "/dev/null", "-q"])
    check("/dev/null: written", rc == 0, err)
    check("/dev/null still a device", stat.S_ISCHR(os.stat("/dev/null").st_mode))
    rc, out, err = run(["decompress", ref_pvr, "-o", "/dev/stdout", "-q"])
    check("/dev/stdout into a pipe", rc == 0 and out == read(ref_png), err)
    check("/dev/stdout still a link", os.path.islink("/dev/stdout"))

    kept = os.path.join(tmp, "kept.pvr")
    with open(kept, "wb") as f:
        f.write(b"old")
    os.chmod(kept, 0o640)
    rc, _, err = run(["compress", png, "-o", kept, "-q"])
    check("existing file keeps its mode",
          rc == 0 and stat.S_IMODE(os.stat(kept).st_mode) == 0o640, err)

    folder = os.path.join(tmp, "folder.png")
    os.makedirs(folder)
    rc, _, err = run(["decompress", ref_pvr, "-o", folder, "-q"])
    stem = os.path.splitext(os.path.basename(ref_pvr))[0]
    check("directory as output: the images go inside it",
          rc == 0 and os.path.isfile(os.path.join(folder, stem + "_level0.png")), err)

    # A read-only folder: as root (who may write anywhere) the command runs as 'nobody'.
    ro = os.path.join(tmp, "ro")
    os.makedirs(ro)
    old = os.path.join(ro, "old.pvr")
    with open(old, "wb") as f:
        f.write(b"old")
    os.chmod(old, 0o644)
    os.chmod(ro, 0o555)
    prefix = []
    if os.geteuid() == 0:
        prefix = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
    os.chmod(png, 0o644)
    can_run = subprocess.run([*prefix, TESSERA, "--version"], capture_output=True).returncode == 0
    if not can_run:
        # The build tree is not reachable for 'nobody' (e.g. a clone under /root).
        print("skip: read-only folder case (tessera cannot run as an unprivileged user here)")
    else:
        p = subprocess.run([*prefix, TESSERA, "compress", png, "-o", old, "-q"],
                           capture_output=True, text=True, timeout=120)
        check("read-only folder: fails", p.returncode == 1 and "Permission denied" in p.stderr,
              p.stderr)
        check("read-only folder: old file intact", read(old) == b"old")
        check("read-only folder: no temporary", os.listdir(ro) == ["old.pvr"],
              str(os.listdir(ro)))
    os.chmod(ro, 0o755)

    # Binary output to a terminal is refused (as zstd does); text commands still print there.
    for args in (["compress", png, "-o", "-"], ["decompress", ref_pvr, "-o", "-"]):
        rc, text = run_on_pty(TESSERA, args)
        check(args[0] + " -o - on a terminal is refused",
              rc == 2 and b"refusing to write" in text and b"PVR" not in text
              and b"PNG" not in text, repr(text[:200]))

    leftovers = [n for r, _, fs in os.walk(tmp) for n in fs if ".tmp" in n]
    check("no temporaries anywhere", not leftovers, str(leftovers))
finally:
    for root, dirs, _ in os.walk(tmp):
        for d in dirs:
            os.chmod(os.path.join(root, d), 0o755)
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
