"""The calc sheet as a document (issue 39): blocks (paragraphs, lists, tables, figures, code),
numbers at engineering precision, and the two renderings, Markdown (report.md) and HTML with
its print CSS (report.html, and through it report.pdf).

Every string of the document is text, never markup: both renderers escape it (`markdown_text`,
html.escape), so a record or file name such as ``<img src=x onerror=alert(1)>`` or ``**x**``
reads as written in both files (docs/python.md, "The calc sheet")."""

from __future__ import annotations

import base64
import html
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

#: significant digits of every number of the sheet computed by sloshdyn, and of the inputs
DIGITS, INPUT_DIGITS = 5, 12
#: the standard acceleration of gravity: accelerations are shown in g = 9.80665 m/s^2
STANDARD_GRAVITY = 9.80665
#: paper sizes of the print CSS (CSS @page size names)
PAPERS = ("a4", "letter")
#: the verdicts of a check (the core's design_checks.csv), printed bold when NOT OK
VERDICTS = ("OK", "NOT OK", "INFO")


# ---- the structured document ----------------------------------------------------------------

@dataclass(frozen=True)
class Paragraph:
    text: str
    code: bool = False    #: verbatim (a code block)


@dataclass(frozen=True)
class Bullets:
    items: list


@dataclass(frozen=True)
class Table:
    header: list
    rows: list
    source: str = ""      #: the CSV file the numbers come from
    caption: str = ""
    wide: bool = False    #: many columns: printed in a smaller font
    form: bool = False    #: a form (the title block): its empty cells are fields to fill in
    style: str = ""       #: a CSS class of the table's own ('calc': a hand calculation)


@dataclass(frozen=True)
class Figure:
    file: str             #: a PNG in the sheet's directory
    caption: str


@dataclass(frozen=True)
class Section:
    title: str
    blocks: list = field(default_factory=list)
    page_break: bool = False   #: printed from a new page (the appendix)


# ---- numbers ----------------------------------------------------------------------------------

def number(value, digits=DIGITS):
    """A number as the sheet prints it: `digits` significant digits, '—' for NaN."""
    value = float(value)
    if math.isnan(value):
        return "—"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return f"{value:.{digits}g}"


def plain_number(value, digits=DIGITS):
    """A number at `digits` significant digits without an exponent where it reads as well
    without (1e-4 <= |x| < 1e12: 4621300, 0.00012346), as the core's hand calculation prints
    the numbers it puts in; '—' for NaN, '' for an empty field."""
    if not isinstance(value, float):
        return value if value != "" else "—"
    if not math.isfinite(value) or not (value == 0 or 1e-4 <= abs(value) < 1e12):
        return number(value, digits)
    return np.format_float_positional(float(f"{value:.{digits}g}"), trim="-")


_NUMBER = re.compile(r"-?\d+(\.\d+)?([eE][-+]?\d+)?")


def _is_number(text):
    return bool(_NUMBER.fullmatch(text))


def _decimals(text):
    """Characters after the decimal point of a number's text (its exponent included)."""
    mantissa, point, rest = text.partition(".")
    return len(rest) if point else -1


def _aligned(cells):
    """The cells of a column, numbers padded on the right with figure spaces (and a
    punctuation space for a missing point) so that, right-aligned in tabular figures, their
    decimal points line up."""
    widths = [_decimals(c) for c in cells if _is_number(c)]
    if not widths:
        return cells
    most = max(widths)
    out = []
    for cell in cells:
        if _is_number(cell):
            missing = most - _decimals(cell)
            if _decimals(cell) < 0 and most >= 0:
                cell, missing = cell + "\u2008", most       # the point's width, then digits
            cell += "\u2007" * missing
        out.append(cell)
    return out


# ---- Markdown ---------------------------------------------------------------------------------

#: characters that start Markdown (CommonMark, GitHub tables) markup inline: escaped by a
#: backslash (an underscore between letters or digits starts none: left as it is); '<' and '>'
#: (raw HTML, autolinks) as entities, '&' only where it would start one
_MARKDOWN_SPECIAL = re.compile(r"([\\`*\[\]|~!#]|(?<!\w)_|_(?!\w))")
_ENTITY = re.compile(r"&(?=#?\w+;)")


def markdown_text(text, block=False):
    """Text that reads as written once a Markdown renderer has rendered it: no HTML, link,
    emphasis, code, table cell or heading can come out of it (one line: newlines become
    spaces). A block's text (a paragraph, a list item) has a list, rule or heading marker at
    its start escaped too."""
    text = " ".join(str(text).splitlines())
    text = _ENTITY.sub("&amp;", text)
    text = _MARKDOWN_SPECIAL.sub(r"\\\1", text)
    text = text.replace("<", "&lt;").replace(">", "&gt;")
    if block:
        text = re.sub(r"^(\s*\d{1,9})([.)])(?=\s|$)", r"\1\\\2", text)
        text = re.sub(r"^(\s*)([-+=])(?=\s|$|\2)", r"\1\\\2", text)
    return text


def _fence(text):
    """A code fence longer than any run of backticks in the text, so that it cannot close."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    return "`" * max(3, longest + 1)


def to_markdown(title, sections):
    m = markdown_text
    lines = [f"# {m(title)}", ""]
    for section in sections:
        lines += [f"## {m(section.title)}", ""]
        for block in section.blocks:
            if isinstance(block, Paragraph) and block.code:
                fence = _fence(block.text)
                lines += [fence, block.text.rstrip("\n"), fence, ""]
            elif isinstance(block, Paragraph):
                lines += [m(block.text, block=True), ""]
            elif isinstance(block, Bullets):
                lines += [f"- {m(item, block=True)}" for item in block.items] + [""]
            elif isinstance(block, Figure):
                lines += [f"![{m(block.caption)}]({block.file})", "",
                          m(block.caption, block=True), ""]
            else:
                if block.caption or block.source:
                    lines += [" ".join(filter(None, (m(block.caption), block.source and
                                                     f"Source: {m(block.source)}"))), ""]
                lines.append("| " + " | ".join(m(h) for h in block.header) + " |")
                lines.append("|" + "---|" * len(block.header))
                lines += ["| " + " | ".join(m(c) for c in row) + " |" for row in block.rows]
                lines.append("")
    return "\n".join(lines)


# ---- HTML and its print CSS -------------------------------------------------------------------

def print_css(paper, title):
    """The sheet's CSS: on screen a column of text; in print (a browser, or WeasyPrint for
    report.pdf) the paper size, page numbers and the title on every page, table headers
    repeated on each page, no heading at a page's foot, figures and table rows kept whole,
    text left-aligned and numbers right-aligned on their decimal point (tabular figures)."""
    size = {"a4": "A4", "letter": "letter"}[paper]
    running = title.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ")
    return f"""
body {{ font-family: "DejaVu Sans", sans-serif; font-size: 10pt; line-height: 1.35;
       max-width: 62em; margin: 2em auto; padding: 0 1em; color: #000; }}
h1 {{ font-size: 16pt; margin: 0 0 0.4em; }}
h2 {{ font-size: 13pt; margin: 1em 0 0.3em; border-bottom: 1px solid #999; }}
h1, h2, .caption {{ break-after: avoid; page-break-after: avoid; text-align: left; }}
p, li, th, td {{ text-align: left; }}
table {{ border-collapse: collapse; margin: 0.3em 0 0.8em; }}
table.wide {{ font-size: 8pt; }}
thead {{ display: table-header-group; }}
tr, figure, pre {{ break-inside: avoid; page-break-inside: avoid; }}
th, td {{ border: 1px solid #aaa; padding: 1px 6px; vertical-align: top; }}
th {{ background: #eee; font-weight: bold; }}
td.num {{ text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }}
table.form {{ font-size: 9pt; }}
table.form td {{ min-width: 12em; height: 1.3em; }}
table.calc {{ width: 100%; font-size: 8.5pt; }}
table.calc td:nth-child(2) {{ width: 20%; }}
table.calc td:nth-child(3) {{ width: 46%; }}
table.calc td:nth-child(6) {{ width: 13%; }}
td.verdict {{ white-space: nowrap; }}
td.NOT-OK {{ font-weight: bold; }}
pre {{ background: #f4f4f4; padding: 0.5em; white-space: pre-wrap; font-size: 8pt; }}
figure {{ margin: 0.5em 0; }}
img {{ max-width: 100%; }}
figcaption {{ font-size: 9pt; }}
section.appendix {{ break-before: page; page-break-before: always; }}
@page {{ size: {size}; margin: 16mm 14mm 18mm 14mm;
        @top-left {{ content: "{running}"; font-size: 8pt; font-family: "DejaVu Sans"; }}
        @bottom-right {{ content: "page " counter(page) " of " counter(pages); font-size: 8pt;
                         font-family: "DejaVu Sans"; }} }}
@media print {{ body {{ max-width: none; margin: 0; padding: 0; }} }}
"""


def to_html(title, sections, directory, paper="a4"):
    """The same document as HTML, self-contained (figures embedded as base64 PNG), with the
    print CSS for `paper` ('a4' or 'letter')."""
    e = html.escape
    parts = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
             f"<title>{e(title)}</title>", f"<style>{print_css(paper, title)}</style>",
             "</head><body>", f"<h1>{e(title)}</h1>"]
    for section in sections:
        parts.append("<section class=\"appendix\">" if section.page_break else "<section>")
        parts.append(f"<h2>{e(section.title)}</h2>")
        for block in section.blocks:
            if isinstance(block, Paragraph):
                parts.append(f"<pre>{e(block.text)}</pre>" if block.code else
                             f"<p>{e(block.text)}</p>")
            elif isinstance(block, Bullets):
                parts.append("<ul>" + "".join(f"<li>{e(item)}</li>" for item in block.items)
                             + "</ul>")
            elif isinstance(block, Figure):
                data = base64.b64encode((Path(directory) / block.file).read_bytes()).decode()
                parts.append(f"<figure><img src=\"data:image/png;base64,{data}\" "
                             f"alt=\"{e(block.caption)}\"><figcaption>{e(block.caption)}"
                             "</figcaption></figure>")
            else:
                parts.append(_html_table(block))
        parts.append("</section>")
    parts.append("</body></html>")
    return "\n".join(parts)


def _breakable(text):
    """A column name that may wrap after its underscores (a zero-width space), so that a table
    of long names fits the page."""
    return text.replace("_", "_\u200b")


def _html_table(block):
    e = html.escape
    parts = []
    if block.caption or block.source:
        parts.append("<p class=\"caption\">" + e(" ".join(filter(None, (
            block.caption, block.source and f"Source: {block.source}")))) + "</p>")
    columns = [_aligned([row[k] for row in block.rows]) for k in range(len(block.header))]
    kind = " ".join(k for k, on in (("wide", block.wide), ("form", block.form),
                                    (block.style, block.style)) if on)
    parts.append((f"<table class=\"{kind}\">" if kind else "<table>") + "<thead><tr>"
                 + "".join(f"<th>{_breakable(e(h))}</th>" for h in block.header)
                 + "</tr></thead><tbody>")
    for i, row in enumerate(block.rows):
        cells = []
        for k, text in enumerate(row):
            shown = columns[k][i]
            kind = ("num" if _is_number(text) or text == "—" else
                    "verdict NOT-OK" if text == "NOT OK" else
                    "verdict" if text in VERDICTS else "")
            cells.append(f"<td class=\"{kind}\">{e(shown)}</td>" if kind else
                         f"<td>{e(shown)}</td>")
        parts.append("<tr>" + "".join(cells) + "</tr>")
    parts.append("</tbody></table>")
    return "".join(parts)
