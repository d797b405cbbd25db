#!/usr/bin/env python3
"""Opens DIR/report.html in headless Chromium and checks it as a reader would see it (docs/output-format.md,
"report.html"):

1. it renders: Chromium loads the page from file:// and runs its load handler, which marks <body> with
   data-rendered="yes" (the DOM is taken with --dump-dom, after the load event, which waits for every image);
2. every image loads: the load handler counts the <img> whose naturalWidth > 0; all must have, and every PNG of the
   directory must be on the page; every link and image is a relative path to a file in the directory;
3. the numbers match the JSON: every <span class="num"> names its result file and a JSON pointer in it; the number
   there must equal data-value, and the text shown must be data-value x data-scale to data-digits digits.

Usage: check_report.py DIR KIND [MIN_NUMBERS]. Chromium: $TURBODYN_CHROMIUM, else chromium, chromium-browser or
google-chrome on PATH (Debian: the package chromium, installed by scripts/install-deps.sh).
"""
import html.parser
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.parse


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def browser():
    env = os.environ.get("TURBODYN_CHROMIUM")
    if env:
        return env
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    fail("no Chromium found (install the Debian package chromium: scripts/install-deps.sh, or set TURBODYN_CHROMIUM)")


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.body = None
        self.images, self.links, self.scripts_with_src, self.numbers = [], [], [], []
        self._num = None  # attributes of the open span.num, and its text so far

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "body":
            self.body = a
        elif tag == "img":
            self.images.append(a.get("src", ""))
        elif tag == "a" and "href" in a:
            self.links.append(a["href"])
        elif tag in ("script", "link", "iframe", "object", "embed") and ("src" in a or "href" in a):
            self.scripts_with_src.append((tag, a.get("src") or a.get("href")))
        elif tag == "span" and a.get("class") == "num":
            self._num = [a, ""]

    def handle_data(self, data):
        if self._num is not None:
            self._num[1] += data

    def handle_endtag(self, tag):
        if tag == "span" and self._num is not None:
            self.numbers.append(tuple(self._num))
            self._num = None


def resolve(doc, pointer):
    node = doc
    for token in pointer.split("/")[1:]:
        token = token.replace("~1", "/").replace("~0", "~")
        node = node[int(token)] if isinstance(node, list) else node[token]
    return node


def local_file(directory, ref, what):
    parts = urllib.parse.urlsplit(ref)
    if parts.scheme or parts.netloc or ref.startswith("/"):
        fail(f"{what} '{ref}' is not a relative link")
    path = os.path.join(directory, urllib.parse.unquote(parts.path))
    if not os.path.isfile(path):
        fail(f"{what} '{ref}' points to a missing file")
    return os.path.basename(path)


def main():
    if len(sys.argv) < 3:
        fail("usage: check_report.py DIR KIND [MIN_NUMBERS]")
    directory, kind = os.path.abspath(sys.argv[1]), sys.argv[2]
    min_numbers = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    report = os.path.join(directory, "report.html")
    if not os.path.isfile(report):
        fail(f"no report.html in {directory}")
    with tempfile.TemporaryDirectory(prefix="turbodyn-chromium-") as profile:
        cmd = [browser(), "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-extensions",
               "--disable-background-networking", f"--user-data-dir={profile}", "--dump-dom",
               "file://" + urllib.parse.quote(report)]
        try:
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=90)
        except subprocess.TimeoutExpired:
            fail("Chromium did not finish within 90 s")
    if run.returncode != 0 or "<body" not in run.stdout:
        fail(f"Chromium exit {run.returncode}: {run.stderr[-2000:]}")
    page = Page()
    page.feed(run.stdout)

    # 1. It renders.
    b = page.body or {}
    if b.get("data-rendered") != "yes":
        fail(f"the page's load handler did not run (body attributes {b})")
    if b.get("data-kind") != kind:
        fail(f"report of kind '{b.get('data-kind')}', expected '{kind}'")
    if page.scripts_with_src:
        fail(f"the page loads other files as scripts or styles: {page.scripts_with_src}")

    # 2. Every image loads, and every picture of the directory is on the page.
    total, loaded = int(b.get("data-images-total", -1)), int(b.get("data-images-loaded", -2))
    if total != len(page.images) or loaded != total:
        fail(f"{loaded} of {total} images loaded ({len(page.images)} on the page); broken: {b.get('data-images-broken')}")
    shown = {local_file(directory, src, "image") for src in page.images}
    for href in page.links:
        local_file(directory, href, "link")
    missing = sorted(f for f in os.listdir(directory) if f.endswith(".png") and f not in shown)
    if missing:
        fail(f"pictures of the directory not on the page: {missing}")

    # 3. The numbers match the JSON.
    files = {}
    for attrs, text in page.numbers:
        name, pointer = attrs["data-file"], attrs["data-pointer"]
        if name not in files:
            with open(os.path.join(directory, local_file(directory, name, "number source"))) as f:
                files[name] = json.load(f)
        try:
            value = resolve(files[name], pointer)
        except (KeyError, IndexError, ValueError, TypeError):
            fail(f"{name}#{pointer}: no such value (page shows '{text}')")
        shown_value = float(attrs["data-value"])
        if not isinstance(value, (int, float)) or not math.isclose(value, shown_value, rel_tol=1e-12, abs_tol=0.0):
            fail(f"{name}#{pointer}: the file holds {value!r}, the page {attrs['data-value']}")
        m = re.search(r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?", text.replace("\u2212", "-"))
        if not m:
            fail(f"{name}#{pointer}: no number in the text '{text}'")
        expected = shown_value * float(attrs["data-scale"])
        digits = int(attrs["data-digits"])
        # Rounded to `digits` significant digits (or to whole numbers for large values): half a unit of the last.
        tolerance = max(0.5 * 10 ** (math.floor(math.log10(abs(expected))) - digits + 1) if expected else 0.0, 0.5
                        if abs(expected) >= 10 ** digits else 0.0) * 1.0001
        if abs(float(m.group(0)) - expected) > tolerance + 1e-300:
            fail(f"{name}#{pointer}: the page shows '{text}', expected {expected!r} to {digits} digits")
    if len(page.numbers) < min_numbers:
        fail(f"only {len(page.numbers)} numbers tied to the result files, expected at least {min_numbers}")
    print(f"ok: {report}: rendered, {loaded} of {total} images loaded, {len(page.numbers)} numbers match "
          f"{', '.join(sorted(files))}")


if __name__ == "__main__":
    main()
