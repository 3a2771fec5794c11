#!/usr/bin/env python3
"""The end of scripts/test.sh: how many tests ran, were skipped and failed, per stage and CTest
label, so that a reader of CI's log sees at once what ran.

    test_summary.py STAGE=BUILD_DIR:JUNIT_XML ... [--counts TSV ...]

Each STAGE=BUILD_DIR:JUNIT_XML is one ctest run (`ctest --output-junit JUNIT_XML` in BUILD_DIR);
the labels come from `ctest --show-only=json-v1` there. A test with several labels counts under
each. --counts TSV adds rows already counted (stage, label, run, skipped, failed: the arm64
stage's, tests/arch/pvrtc_arch_bytes.sh). A stage whose JUnit file is missing (the run stopped
before it) is listed as not run. "run" counts the tests that ran to a verdict, failed included.
"""
import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict
from pathlib import Path


def labels_of(build_dir):
    out = subprocess.run(["ctest", "--test-dir", build_dir, "--show-only=json-v1"],
                         capture_output=True, text=True, check=True).stdout
    labels = {}
    for test in json.loads(out)["tests"]:
        props = {p["name"]: p["value"] for p in test.get("properties", [])}
        labels[test["name"]] = props.get("LABELS") or ["(none)"]
    return labels


def count_stage(build_dir, junit):
    labels = labels_of(build_dir)
    rows = defaultdict(lambda: [0, 0, 0])  # label -> run, skipped, failed
    for case in ET.parse(junit).getroot().iter("testcase"):
        status = case.get("status", "run")
        for label in labels.get(case.get("name"), ["(none)"]):
            row = rows[label]
            if status in ("notrun", "disabled"):
                row[1] += 1
            else:
                row[0] += 1
                row[2] += status == "fail"
    return rows


def main(argv):
    table = []  # (stage, label, run, skipped, failed)
    missing = []
    args = iter(argv)
    for arg in args:
        if arg == "--counts":
            path = Path(next(args))
            if not path.is_file():
                missing.append(f"{path} (not written: the stage did not run)")
                continue
            for line in path.read_text().splitlines():
                stage, label, run, skipped, failed = line.split("\t")
                table.append([stage, label, int(run), int(skipped), int(failed)])
            continue
        stage, spec = arg.split("=", 1)
        build_dir, junit = spec.split(":", 1)
        if not Path(junit).is_file():
            missing.append(f"{stage}: not run")
            continue
        for label, (run, skipped, failed) in sorted(count_stage(build_dir, junit).items()):
            table.append([stage, label, run, skipped, failed])
    # Rows of one stage and label (the arm64 programs) added up.
    merged = {}
    for stage, label, run, skipped, failed in table:
        row = merged.setdefault((stage, label), [0, 0, 0])
        row[0] += run
        row[1] += skipped
        row[2] += failed
    print("== Tests per stage and label (run = ran to a verdict, failed included)")
    head = ("stage", "label", "run", "skipped", "failed")
    rows = [(s, l, str(r), str(k), str(f)) for (s, l), (r, k, f) in merged.items()]
    widths = [max(len(x[i]) for x in [head, *rows]) for i in range(5)]
    for row in [head, *rows]:
        print("  ".join(c.ljust(w) if i < 2 else c.rjust(w)
                        for i, (c, w) in enumerate(zip(row, widths))))
    total = [sum(v[i] for v in merged.values()) for i in range(3)]
    print(f"all: {total[0]} run, {total[1]} skipped, {total[2]} failed")
    for line in missing:
        print(f"not counted: {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
