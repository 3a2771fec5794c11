"""Shared by the `tessera view` tests (tests/cli/view_*_test.py): the arguments CTest runs them
with, whether the browser parts can run (Debian's chromium driven by puppeteer-core), and the
start-up JSON a page carries.

Each test is run as `view_X_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]` and drives
its own tests/cli/view_X.mjs.
"""
import json
import os
import shutil
import subprocess
import sys

from cli_harness import finish, missing_part


class ViewTest:
    """The command line of a view test named `name` ("view_cube")."""

    def __init__(self, name):
        here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli")
        self.tessera = os.path.abspath(sys.argv[1])
        self.puppeteer = sys.argv[2] if len(sys.argv) > 2 else ""
        self.out = os.path.abspath(sys.argv[3] if len(sys.argv) > 3 else name + "_out")
        self.chromium = sys.argv[4] if len(sys.argv) > 4 else shutil.which("chromium")
        self.script = os.path.abspath(os.path.join(here, name + ".mjs"))

    def browser_missing(self):
        """(part, why) when the browser parts cannot run, else None."""
        if not self.chromium or not os.path.exists(self.chromium):
            return "chromium", "chromium not found (scripts/setup.sh installs it)"
        if not shutil.which("node"):
            return "puppeteer", "node not found (scripts/setup.sh installs nodejs)"
        if not self.puppeteer or not os.path.isfile(
                os.path.join(self.puppeteer, "node_modules", "puppeteer-core", "package.json")):
            return "puppeteer", (f"puppeteer-core not found in '{self.puppeteer}' "
                                 "(scripts/setup.sh installs it; -DTESSERA_PUPPETEER=DIR)")
        return None

    def note_missing_browser(self):
        """For a test with parts that need no browser: the browser parts are skipped with a
        note (or fail under TESSERA_TEST_REQUIRE); returns whether they are missing."""
        missing = self.browser_missing()
        if missing:
            missing_part(missing[0], missing[1] + ": the browser parts are skipped")
        return missing is not None

    def require_browser(self):
        """For a test that is all browser: exits 77 (skipped) without one, or fails under
        TESSERA_TEST_REQUIRE."""
        missing = self.browser_missing()
        if missing:
            missing_part(missing[0], missing[1] + ": skipped")
            sys.exit(finish() or 77)

    def run(self, *args, cwd=None):
        """`tessera ARGS`: (exit code, stdout, stderr)."""
        p = subprocess.run([self.tessera, *args], capture_output=True, text=True, timeout=600,
                           cwd=cwd)
        return p.returncode, p.stdout, p.stderr


def page_data(html):
    """The start-up JSON of a page: `html` is its text, or the path of a static view."""
    if not html.lstrip().startswith("<"):
        with open(html, encoding="utf-8") as f:
            html = f.read()
    start = html.index('<script id="tessera-data" type="application/json">')
    start = html.index(">", start) + 1
    return json.loads(html[start:html.index("</script>", start)])
