"""Helpers shared by the benchmark scripts in bench/."""
import os
import platform


def cpu_model():
    """The CPU's model name from /proc/cpuinfo (or what platform knows)."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def write_report(path, lines, notes_marker):
    """Writes a Markdown report atomically (a temporary file, then a rename). Hand-written notes
    after `notes_marker` in the existing file survive the regeneration; a new file gets the
    marker alone, for notes to be added under it."""
    notes = ""
    if os.path.isfile(path):
        with open(path) as f:
            old = f.read()
        if notes_marker in old:
            notes = old[old.index(notes_marker):]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join([*lines, notes or notes_marker + "\n"]))
    os.replace(tmp, path)
