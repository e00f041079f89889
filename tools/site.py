#!/usr/bin/env python3
"""`./springlab site OUT`: the course as a static site, deployable as it is (GitHub Pages or
any static host; no server code, no cross-origin isolation).

  OUT/index.html                 the labs, their handouts and READMEs
  OUT/handouts/<lab>.html        each handout, rendered by Python-Markdown (Debian:
                                 python3-markdown); a section (## heading) that names a scene
                                 (scenes/NAME.json) has that scene live beside it
  OUT/handouts/images/           the committed charts the handouts show
  OUT/labs/<lab>.html            each lab's README
  OUT/web/                       the viewer in the browser (tools/web_build.sh), the pages
                                 the sections embed

usage: tools/site.py OUT [--no-web]   (--no-web: OUT/web/ is built already)
"""
import argparse
import html
import pathlib
import re
import shutil
import subprocess
import sys

try:
    import markdown
except ImportError:
    sys.exit("springlab site: Python-Markdown is missing (Debian: apt-get install python3-markdown; "
             "elsewhere: pip install markdown)")

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXTENSIONS = ["tables", "fenced_code", "toc", "sane_lists", "attr_list"]
SCENE = re.compile(r"scenes/([a-z0-9_]+\.json)")
LINK = re.compile(r'(href|src)="([^"#:?]+\.md)(#[^"]*)?"')

STYLE = """
body { margin: 0; font: 16px/1.55 system-ui, sans-serif; color: #1d2129; background: #fbfbfc; }
header { padding: 12px 24px; background: #14161b; color: #e8e9ee; }
header a { color: #9fc3ff; margin-right: 18px; text-decoration: none; }
main { max-width: 1500px; margin: 0 auto; padding: 8px 24px 48px; }
section.live { display: grid; grid-template-columns: minmax(0, 1fr) minmax(380px, 44%); gap: 24px; align-items: start; }
section.live aside { position: sticky; top: 12px; }
section.live iframe { width: 100%; height: 460px; border: 1px solid #c9ccd3; border-radius: 6px; background: #1c1f26; }
aside p { margin: 4px 0; font-size: 13px; color: #5b6070; }
pre { background: #f0f1f4; padding: 10px 12px; overflow-x: auto; border-radius: 4px; }
code { font-size: 90%; }
table { border-collapse: collapse; margin: 12px 0; }
th, td { border: 1px solid #d3d6dd; padding: 4px 10px; text-align: left; }
img { max-width: 100%; }
@media (max-width: 900px) { section.live { display: block; } }
"""


def page(title, body, depth):
    """A whole HTML page; depth is how many folders below OUT it sits."""
    up = "../" * depth
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)}</title><link rel="icon" href="data:,"><style>{STYLE}</style></head>
<body><header><a href="{up}index.html">springlab</a><a href="{up}web/index.html">all scenes live</a></header>
<main>
{body}
</main></body></html>
"""


def sections(text):
    """The Markdown split before each `## ` heading that is not inside a code block."""
    parts, current, fenced = [], [], False
    for line in text.splitlines(keepends=True):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        if line.startswith("## ") and not fenced and current:
            parts.append("".join(current))
            current = []
        current.append(line)
    parts.append("".join(current))
    return parts


LIST_ITEM = re.compile(r"^\s*(?:[-*+]|\d+[.)])\s")


def lists_after_paragraphs(text):
    """A blank line before a list that follows a paragraph line: GitHub's Markdown starts the
    list there, Python-Markdown needs the blank line (code blocks left as they are)."""
    out, fenced, previous = [], False, ""
    for line in text.splitlines(keepends=True):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        if (not fenced and LIST_ITEM.match(line) and previous.strip() and not LIST_ITEM.match(previous)
                and not previous.startswith(("    ", "\t"))):
            out.append("\n")
        out.append(line)
        previous = line
    return "".join(out)


def render(text, pages):
    """Markdown to HTML; links to the Markdown files the site renders go to their pages."""
    body = markdown.markdown(lists_after_paragraphs(text), extensions=EXTENSIONS)

    def link(match):
        attribute, target, anchor = match.group(1), match.group(2), match.group(3) or ""
        name = pathlib.PurePosixPath(target).name
        return f'{attribute}="{pages.get(target, pages.get(name, target))}{anchor}"' if (
            target in pages or name in pages) else match.group(0)

    return LINK.sub(link, body)


def handout_page(path, pages, scenes):
    """A handout: each section that names a scene with that scene live beside it."""
    out = []
    for chunk in sections(path.read_text()):
        body = render(chunk, pages)
        named = [name for name in SCENE.findall(chunk) if name in scenes]
        if named:
            scene = named[0]
            out.append(f'<section class="live"><div>{body}</div><aside>'
                       f'<iframe src="../web/index.html?scene={scene}&amp;embed" loading="lazy" '
                       f'title="{html.escape(scenes[scene])}"></iframe>'
                       f'<p>Live: {html.escape(scenes[scene])} (<code>scenes/{scene}</code>). Drag to orbit, '
                       f'Shift-drag pulls a mass; <a href="../web/index.html?scene={scene}">full page</a>.</p>'
                       f'</aside></section>')
        else:
            out.append(f"<section>{body}</section>")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--no-web", action="store_true", help="OUT/web/ is built already")
    args = parser.parse_args()
    out = args.out.resolve()
    (out / "handouts").mkdir(parents=True, exist_ok=True)
    (out / "labs").mkdir(parents=True, exist_ok=True)

    # The viewer's pages first: the handouts embed them.
    if not args.no_web:
        if subprocess.run([str(ROOT / "tools" / "web_build.sh"), "--out", str(out / "web")]).returncode != 0:
            sys.exit("springlab site: the browser build failed (above)")
    import json
    scenes = {p.name: json.loads(p.read_text()).get("name", p.stem) for p in sorted((ROOT / "scenes").glob("*.json"))}

    handouts = sorted((ROOT / "handouts").glob("*.md"))
    readmes = sorted((ROOT / "labs").glob("*/README.md"))
    # Where each Markdown file of the site is, seen from a page one folder below OUT.
    pages = {h.name: f"../handouts/{h.stem}.html" for h in handouts}
    pages.update({f"../labs/{r.parent.name}/README.md": f"../labs/{r.parent.name}.html" for r in readmes})

    index = ["<h1>springlab: mass-spring physics</h1>",
             "<p>Three labs, each a handout with its scenes running beside the text (WebGL2, one thread: "
             "nothing to install), and the lab's README.</p><ul>"]
    for h in handouts:
        title = next((l[2:].strip() for l in h.read_text().splitlines() if l.startswith("# ")), h.stem)
        (out / "handouts" / f"{h.stem}.html").write_text(page(title, handout_page(h, pages, scenes), 1))
        readme = ROOT / "labs" / h.stem / "README.md"
        extra = f' (<a href="labs/{h.stem}.html">README</a>)' if readme.exists() else ""
        index.append(f'<li><a href="handouts/{h.stem}.html">{html.escape(title)}</a>{extra}</li>')
    index.append('</ul><p><a href="web/index.html">Every scene in the viewer</a>.</p>')
    for r in readmes:
        title = f"{r.parent.name}: README"
        (out / "labs" / f"{r.parent.name}.html").write_text(page(title, render(r.read_text(), pages), 1))
    (out / "index.html").write_text(page("springlab", "\n".join(index), 0))

    # The committed charts (PNG) the handouts show.
    images = ROOT / "handouts" / "images"
    if images.exists():
        shutil.rmtree(out / "handouts" / "images", ignore_errors=True)
        shutil.copytree(images, out / "handouts" / "images", ignore=shutil.ignore_patterns("*.csv", "*.json", "*.svg"))
    print(f"springlab site: wrote {out}/index.html ({len(handouts)} handouts, {len(readmes)} READMEs); "
          f"serve it with python3 -m http.server --directory {out}")


if __name__ == "__main__":
    main()
