"""Shared plumbing of the CLI test scripts: running a program, counting checks, the summary.

Each script keeps its own `expect_error` (the error contracts differ per command) and calls
`check` from here; `finish()` prints the closing 'N passed, M failed' line CTest logs show.
"""
import os
import pty
import struct
import subprocess
import sys
import zlib

_passed = 0
_failures = []


def run_command(cmd, timeout=300):
    """Runs `cmd` (a list) and returns (exit code, stdout, stderr) as text."""
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def run_on_pty(program, args):
    """Runs `program` with stdin, stdout and stderr on a new terminal; returns (exit code,
    everything it wrote, as bytes)."""
    pid, fd = pty.fork()
    if pid == 0:
        os.execv(program, [program, *args])
    text = b""
    while True:
        try:
            chunk = os.read(fd, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        text += chunk
    _, status = os.waitpid(pid, 0)
    os.close(fd)
    return os.WEXITSTATUS(status), text


def png_chunk(kind, data):
    """One PNG chunk: the length of `data`, the 4-byte `kind`, `data` and the CRC."""
    c = kind + data
    return struct.pack(">I", len(data)) + c + struct.pack(">I", zlib.crc32(c) & 0xFFFFFFFF)


def png_bytes(width, height, channels, pixel, level=-1):
    """An 8-bit PNG made with the standard library: `channels` 1 to 4 (grey, grey + alpha, RGB,
    RGBA), filter None on every row, zlib `level` (-1: zlib's default); pixel(x, y) returns a
    tuple of at least `channels` ints."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        for x in range(width):
            raw.extend(pixel(x, y)[:channels])
    ihdr = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
            + png_chunk(b"IDAT", zlib.compress(bytes(raw), level)) + png_chunk(b"IEND", b""))


def write_png(path, width, height, pixel, alpha):
    """Writes an 8-bit RGB or RGBA PNG (`png_bytes`); pixel(x, y) returns a tuple of 3 or 4 ints.
    Returns `path`."""
    with open(path, "wb") as f:
        f.write(png_bytes(width, height, 4 if alpha else 3, pixel))
    return path


def check(name, cond, detail="", show_passed=False):
    """Counts one check; prints and remembers a failure (and, with `show_passed`, prints a
    passed check with its detail: "ok   name: detail")."""
    global _passed
    if cond:
        _passed += 1
        if show_passed:
            print(f"ok   {name}: {detail}")
    else:
        _failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


def expect_error(run, name, args, code, must_name=None):
    """Runs `run(*args)` and checks the error contract: exit `code`; for bad input (1) exactly
    one line on stderr; `must_name` (a path, usually) appears in it. Returns stderr."""
    rc, _, err = run(*args)
    lines = [line for line in err.splitlines() if line.strip()]
    check(name + " exit code", rc == code, f"rc={rc} stderr={err!r}")
    if code == 1:
        check(name + " one line", len(lines) == 1, f"stderr={err!r}")
    if must_name:
        check(name + " names it", must_name in err, f"stderr={err!r}")
    return err


SKIP_CODE = 77  # CTest's SKIP_RETURN_CODE for these scripts (tests/*/CMakeLists.txt)


def required(what):
    """Whether the run must have `what` ("gl", "pvrtextool", "shared", "ktx-parse"): named in the
    comma-separated TESSERA_TEST_REQUIRE, or that variable is "all" (the README's test command,
    scripts/test.sh, sets "all")."""
    wanted = [w.strip() for w in os.environ.get("TESSERA_TEST_REQUIRE", "").split(",")]
    return "all" in wanted or what in wanted


def skip_or_fail(what, message):
    """A whole script cannot run without `what`: exits SKIP_CODE (CTest reports it skipped) with
    `message`, or exit 1 when the run requires `what`."""
    if required(what):
        print(f"FAIL: {message} (TESSERA_TEST_REQUIRE asks for {what})")
        sys.exit(1)
    print(f"SKIP: {message}")
    sys.exit(SKIP_CODE)


def missing_part(what, message):
    """A part of a script cannot run without `what`: prints `message` and goes on, or counts a
    failure when the run requires `what`."""
    if required(what):
        check(message, False, f"TESSERA_TEST_REQUIRE asks for {what}")
    else:
        print(f"note: {message}")


def finish():
    """Prints the summary line and returns the process exit code (1 if anything failed)."""
    print(f"{_passed} passed, {len(_failures)} failed")
    return 1 if _failures else 0
