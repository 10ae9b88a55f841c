#!/usr/bin/python3
"""REPORT.md -> REPORT.html: the report as one page, its figures as the files beside it (issue 13 item 3, issue 35
item 5: the page with every SVG inline was 39 MB).

The Markdown is rendered by Debian's python3-markdown (tables, fenced code, and heading anchors from its toc
extension, so every study's section has an id to link to). Every link to a plot, plots/<study>/<name>.png, stays a
link, now to the figure on the page; the figure follows the paragraph, list item or table row that links it, as an
image of the .svg that plots/make_plots.sh writes beside each .png, by its path relative to the page (so the page is
read beside plots/, as REPORT.html is in the repository). A linked plot without an .svg is named in a visible note
and on stderr, never silently dropped.

Usage: report_html.py REPORT.md REPORT.html
"""
import html
import pathlib
import re
import sys

import markdown

PLOT_LINK = re.compile(r"\]\((plots/[^)\s]+)\.png\)")


def figure_block(root: pathlib.Path, plot: str, number: int, missing: list) -> str:
    anchor = "fig-" + re.sub(r"[^A-Za-z0-9]+", "-", plot)
    svg_path = root / (plot + ".svg")
    caption = html.escape(plot + ".png")
    if not svg_path.is_file():
        missing.append(plot)
        return (f'<figure id="{anchor}" class="missing"><figcaption>{caption}: no SVG beside it '
                f'(run make plots)</figcaption></figure>')
    source = html.escape(plot + ".svg", quote=True)
    return (f'<figure id="{anchor}"><img src="{source}" alt="{caption}" style="max-width:100%;height:auto">'
            f'<figcaption>{caption}</figcaption></figure>')


def with_figures(text: str, root: pathlib.Path, missing: list) -> tuple:
    """The Markdown with a placeholder block after each block (paragraph, list, table) that links plots, and the
    figures' HTML for each placeholder (put in after the conversion, which would otherwise wrap them in
    paragraphs)."""
    blocks = re.split(r"\n\s*\n", text)
    out, seen, figures_of, number = [], set(), [], 0
    for block in blocks:
        out.append(block)
        plots = [p for p in PLOT_LINK.findall(block) if p not in seen]
        if not plots or block.lstrip().startswith("```"):
            continue
        figures = []
        for plot in dict.fromkeys(plots):
            seen.add(plot)
            number += 1
            figures.append(figure_block(root, plot, number, missing))
        out.append(f'<div class="figures" id="figures-{len(figures_of)}"></div>')
        figures_of.append("\n".join(figures))
    body = "\n\n".join(out)
    # The links point at the figures on the page.
    body = PLOT_LINK.sub(lambda m: "](#fig-" + re.sub(r"[^A-Za-z0-9]+", "-", m.group(1)) + ")", body)
    return body, figures_of


STYLE = """
body { font-family: sans-serif; max-width: 75em; margin: 2em auto; padding: 0 1em; line-height: 1.45; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; display: block; overflow-x: auto; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; }
th { background: #eee; }
code { background: #f4f4f4; padding: 0 0.2em; }
pre { background: #f4f4f4; padding: 0.6em; overflow-x: auto; }
figure { margin: 1em 0; }
figure.missing { color: #a00; }
figcaption { font-size: 0.85em; color: #555; }
.headerlink { text-decoration: none; color: #aaa; margin-left: 0.3em; }
"""


def render(source: pathlib.Path) -> tuple:
    missing = []
    text, figures_of = with_figures(source.read_text(encoding="utf-8"), source.parent, missing)
    md = markdown.Markdown(extensions=["tables", "fenced_code", "toc", "sane_lists"],
                           extension_configs={"toc": {"permalink": True}})
    body = md.convert(text)
    for k, figures in enumerate(figures_of):
        placeholder = f'<div class="figures" id="figures-{k}"></div>'
        if placeholder not in body:
            raise RuntimeError(f"report_html: figure block {k} lost in the conversion")
        body = body.replace(placeholder, f'<div class="figures" id="figures-{k}">\n{figures}\n</div>', 1)
    page = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<title>beamid report</title>\n<style>" + STYLE + "</style>\n</head>\n<body>\n" + body +
            "\n</body>\n</html>\n")
    return page, missing


def main(argv: list) -> int:
    if len(argv) != 3:
        print("usage: report_html.py REPORT.md REPORT.html", file=sys.stderr)
        return 2
    source, target = pathlib.Path(argv[1]), pathlib.Path(argv[2])
    if not source.is_file():
        print(f"report_html: {source}: not a file", file=sys.stderr)
        return 2
    page, missing = render(source)
    temporary = target.with_name(target.name + ".tmp")
    temporary.write_text(page, encoding="utf-8")
    temporary.replace(target)  # a reader sees the old page or the new one, never half
    for plot in missing:
        print(f"report_html: {plot}.png is linked but has no {plot}.svg (run make plots)", file=sys.stderr)
    print(f"report_html: {target} ({len(page) / 1e6:.1f} MB, {page.count('<figure')} figures, "
          f"{page.count('<table')} tables)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
