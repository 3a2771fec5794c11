#!/usr/bin/env python3
"""`tessera compress IN... -o OUTDIR/`: files, folders (--recursive), @lists; output names follow
the inputs; every file's bytes equal a single-file run's for any -j; one bad file fails alone
(one line, exit 1 at the end, no output for it); --json lines and summary; --skip-up-to-date
resumes and notices changed inputs and options.

Usage: compress_batch_test.py PATH/TO/tessera
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish  # noqa: E402

TESSERA = sys.argv[1]


def run(*args):
    p = subprocess.run([TESSERA, *args], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def read(path):
    with open(path, "rb") as f:
        return f.read()


tmp = tempfile.mkdtemp(prefix="tessera-batch-")
try:
    rc, _, err = run("demo", "-o", os.path.join(tmp, "d"), "--size", "64")
    check("demo for inputs", rc == 0, err)
    img = os.path.join(tmp, "d", "img")
    src = os.path.join(tmp, "src")
    os.makedirs(os.path.join(src, "sub", "deeper"))
    names = ["images-noise.png", "images-foliage.png", "images-bricks.png"]
    shutil.copy(os.path.join(img, names[0]), os.path.join(src, "a.png"))
    shutil.copy(os.path.join(img, names[1]), os.path.join(src, "sub", "b.PNG"))
    shutil.copy(os.path.join(img, names[2]), os.path.join(src, "sub", "deeper", "c.png"))
    with open(os.path.join(src, "sub", "notes.txt"), "w") as f:
        f.write("not an image")
    with open(os.path.join(src, "sub", "broken.png"), "wb") as f:
        f.write(read(os.path.join(src, "a.png"))[:50])

    # Folder, recursive, 2 workers, --json.
    out = os.path.join(tmp, "out")
    rc, stdout, err = run("-j", "2", "compress", src, "-o", out + "/", "--recursive", "--json",
                          "--quality", "fast")
    lines = [json.loads(line) for line in stdout.splitlines()]
    check("one bad file: exit 1", rc == 1, err)
    check("one bad file: one line naming it",
          len(err.splitlines()) == 1 and "broken.png" in err, err)
    check("json: a line per file and a summary", len(lines) == 5, stdout)
    check("json: input order", [os.path.relpath(j["input"], src) for j in lines[:4]] ==
          ["a.png", "sub/b.PNG", "sub/broken.png", "sub/deeper/c.png"], stdout)
    summary = lines[-1]
    check("summary counts", summary.get("summary") and summary["done"] == 3 and
          summary["failed"] == 1 and summary["files"] == 4, stdout)
    check("failed line", lines[2]["status"] == "failed" and "broken.png" in lines[2]["error"])
    check("psnr in json", lines[0]["psnr_rgb"] > 20 and 0 < lines[0]["ssim_gray"] <= 1, stdout)
    expected = {"a.pvr", "sub/b.pvr", "sub/deeper/c.pvr"}
    made = {os.path.relpath(os.path.join(r, n), out) for r, _, fs in os.walk(out) for n in fs}
    check("outputs mirror the tree, none for the bad file", made == expected, str(made))

    # Each output equals a single-file run, whatever -j.
    for rel_in, rel_out in (("a.png", "a.pvr"), ("sub/b.PNG", "sub/b.pvr"),
                            ("sub/deeper/c.png", "sub/deeper/c.pvr")):
        single = os.path.join(tmp, "single.pvr")
        rc, _, err = run("-j", "1", "compress", os.path.join(src, rel_in), "-o", single, "-q",
                         "--quality", "fast")
        check("single run " + rel_in, rc == 0, err)
        check("batch bytes == single-file bytes: " + rel_in,
              read(single) == read(os.path.join(out, rel_out)))
    out1 = os.path.join(tmp, "out-j1")
    run("-j", "1", "compress", src, "-o", out1, "--recursive", "-q", "--quality", "fast")
    check("-j 1 and -j 2 give the same files",
          all(read(os.path.join(out, e)) == read(os.path.join(out1, e)) for e in expected))

    # Without --recursive a folder gives its own images only; KTX by --container.
    out2 = os.path.join(tmp, "out2")
    rc, stdout, err = run("compress", src, "-o", out2, "--container", "ktx", "-q")
    check("non-recursive", rc == 0 and os.listdir(out2) == ["a.ktx"], f"{os.listdir(out2)} {err}")
    check("quiet batch prints nothing", stdout == "" and err == "", stdout + err)

    # @list files (comments and blank lines skipped), plain files, a missing one failing alone.
    lst = os.path.join(tmp, "list.txt")
    with open(lst, "w") as f:
        f.write(f"# textures\n{os.path.join(src, 'a.png')}\n\n{os.path.join(src, 'nope.png')}\n"
                f"{os.path.join(src, 'sub', 'deeper', 'c.png')}\r\n")
    out3 = os.path.join(tmp, "out3")
    rc, stdout, err = run("compress", "@" + lst, "-o", out3)
    check("@list: missing file fails alone", rc == 1 and "nope.png: cannot open" in err, err)
    check("@list outputs", sorted(os.listdir(out3)) == ["a.pvr", "c.pvr"], str(os.listdir(out3)))
    check("human summary", "compressed 2 of 3 file(s)" in stdout and "1 failed" in stdout, stdout)

    # Two inputs naming one output: the second fails, the first is written.
    clash = os.path.join(tmp, "clash")
    os.makedirs(clash)
    shutil.copy(os.path.join(src, "a.png"), os.path.join(clash, "a.png"))
    out4 = os.path.join(tmp, "out4")
    rc, _, err = run("compress", os.path.join(src, "a.png"), os.path.join(clash, "a.png"), "-o",
                     out4)
    check("name clash fails alone", rc == 1 and "is also made from" in err, err)
    check("name clash: first kept", os.listdir(out4) == ["a.pvr"])

    # --skip-up-to-date: a second run skips everything; a touched input or new options redo.
    out5 = os.path.join(tmp, "out5")
    args = ["compress", os.path.join(src, "a.png"), os.path.join(src, "sub", "b.PNG"), "-o", out5,
            "--skip-up-to-date", "--json", "--quality", "fast"]
    rc, stdout, err = run(*args)
    check("resume: first run", rc == 0, err)
    check("resume: sidecars written", os.path.isfile(os.path.join(out5, "a.pvr.json")))
    first = read(os.path.join(out5, "a.pvr"))
    rc, stdout, err = run(*args)
    s = [json.loads(line) for line in stdout.splitlines()]
    check("resume: everything skipped", rc == 0 and s[-1]["skipped"] == 2 and s[-1]["done"] == 0,
          stdout)
    time.sleep(0.02)
    os.utime(os.path.join(src, "a.png"))  # a newer input
    rc, stdout, err = run(*args)
    s = [json.loads(line) for line in stdout.splitlines()]
    check("resume: touched input redone", s[0]["status"] == "done" and s[1]["status"] == "skipped",
          stdout)
    check("resume: same bytes", read(os.path.join(out5, "a.pvr")) == first)
    rc, stdout, err = run(*args[:-1], "normal")
    s = [json.loads(line) for line in stdout.splitlines()]
    check("resume: other options redo all", s[-1]["done"] == 2, stdout)

    # Usage.
    rc, _, err = run("compress", os.path.join(src, "a.png"), os.path.join(src, "a.png"), "-o", "-")
    check("batch to '-' is a usage error", rc == 2 and "folder" in err, err)
    rc, _, err = run("compress", "@" + os.path.join(tmp, "nolist.txt"), "-o", out)
    check("missing @list is a usage error", rc == 2 and "nolist.txt" in err, err)
    leftovers = [n for r, _, fs in os.walk(tmp) for n in fs if ".tmp" in n]
    check("no temporaries", not leftovers, str(leftovers))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
