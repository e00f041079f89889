#!/usr/bin/env python3
"""The course site's test (ctest web.site): `tools/site.py OUT` writes a site whose every
relative link and embedded frame resolves to a file of the site (its #anchor to an id of that
page), whose handout sections embed scenes the site's viewer has, and which needs no server
code. Exit 77 (ctest: skipped) with the reason printed when Emscripten or Python-Markdown is
missing.

usage: check_site.py --root ROOT --python PYTHON [--out DIR]
"""
import argparse
import html.parser
import pathlib
import re
import shutil
import subprocess
import sys
import urllib.parse

SKIP = 77


class Links(html.parser.HTMLParser):
    """The href/src targets and the ids of one page."""

    def __init__(self):
        super().__init__()
        self.targets, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name in ("href", "src") and value is not None:
                self.targets.append((tag, value))
            if name == "id" and value:
                self.ids.add(value)


def parse(path):
    links = Links()
    links.feed(path.read_text())
    return links


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", required=True, type=pathlib.Path)
    parser.add_argument("--python", default="/usr/bin/python3", help="a Python with Python-Markdown")
    parser.add_argument("--out", type=pathlib.Path)
    args = parser.parse_args()
    root = args.root.resolve()
    out = (args.out or root / "out" / "site-test").resolve()

    missing = []
    if not shutil.which("emcc"):
        missing.append("emcc (Debian: apt-get install emscripten)")
    if subprocess.run([args.python, "-c", "import markdown"], capture_output=True).returncode != 0:
        missing.append(f"Python-Markdown for {args.python} (Debian: apt-get install python3-markdown)")
    if missing:
        print("SKIPPED: the site test needs " + " and ".join(missing))
        return SKIP

    shutil.rmtree(out, ignore_errors=True)
    if subprocess.run([args.python, str(root / "tools" / "site.py"), str(out)]).returncode != 0:
        print("FAILED: tools/site.py failed")
        return 1

    # The scenes the site's viewer runs (web/scenes.js).
    scenes = set(re.findall(r'"file": "([^"]+)"', (out / "web" / "scenes.js").read_text()))
    pages = {p: parse(p) for p in out.rglob("*.html")}
    failures, checked, frames, external = [], 0, 0, []
    for page, links in pages.items():
        for tag, target in links.targets:
            parts = urllib.parse.urlsplit(target)
            if parts.scheme == "data":
                continue  # inline: nothing to fetch
            if parts.scheme or parts.netloc:
                external.append(target)  # not fetched: the test runs without a network
                continue
            checked += 1
            path = (page.parent / urllib.parse.unquote(parts.path)).resolve() if parts.path else page
            if not path.is_relative_to(out) or not path.is_file():
                failures.append(f"{page.relative_to(out)}: {target} does not resolve to a file of the site")
                continue
            if parts.fragment and path.suffix == ".html" and parts.fragment not in pages[path].ids:
                failures.append(f"{page.relative_to(out)}: {target}: no id '{parts.fragment}' in {path.name}")
            if tag == "iframe":
                frames += 1
                scene = urllib.parse.parse_qs(parts.query).get("scene", [""])[0]
                if scene not in scenes:
                    failures.append(f"{page.relative_to(out)}: embeds scene '{scene}', which the site's viewer lacks")
    # Every handout with a live scene, and nothing a static host cannot serve.
    if frames == 0:
        failures.append("no handout section embeds a live scene")
    server_code = [p for p in out.rglob("*") if p.suffix in (".php", ".py", ".cgi")]
    failures += [f"{p.relative_to(out)}: server code in a static site" for p in server_code]
    for failure in failures:
        print("FAILED: " + failure)
    print(f"site: {len(pages)} pages, {checked} links ({frames} live scenes) checked; "
          f"{len(external)} links to other sites left unchecked")
    print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
