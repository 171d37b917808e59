"""Reading a calc sheet back, independently of sloshdyn's renderers (tests of issues 25 and 39):
report.md rendered by markdown-it-py (CommonMark with tables), report.html parsed by
html.parser, the CSV files by the csv module; numbers compared with the CSV values at the
printed precision, units converted with the factors below (typed from their definitions)."""

import csv
import html.parser
import math
import re

from markdown_it import MarkdownIt

#: engineering unit -> SI factor (1 kN = 1e3 N, 1 t = 1e3 kg, 1 g = 9.80665 m/s^2 standard)
FACTORS = {"kN": 1e3, "MN": 1e6, "kN·m": 1e3, "MN·m": 1e6, "kPa": 1e3, "kN/m": 1e3, "t": 1e3,
           "g": 9.80665, "MN·m/rad": 1e6, "MN·m·s/rad": 1e6}
#: what the HTML adds for print: figure and punctuation spaces (decimal alignment), zero-width
#: spaces (where a column name may wrap)
PRINT_SPACES = dict.fromkeys(map(ord, "\u2007\u2008\u200b"))


def read_csv(path):
    with open(path, newline="", encoding="utf-8", errors="backslashreplace") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def one_row(path):
    columns, rows = read_csv(path)
    return dict(zip(columns, rows[0]))


class Page(html.parser.HTMLParser):
    """The blocks of an HTML page in order: ('table', source, header, rows) with the source
    named by the paragraph before it ("Source: X.csv"), ('p', text), ('li', text),
    ('h2', text), ('img', src, alt), ('pre', text); and every tag met (tag, attributes,
    whether inside a <pre>)."""

    def __init__(self, text):
        super().__init__()
        self.blocks, self.tags, self._text, self._table, self._last_p = [], [], None, None, ""
        self._in_pre = False
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs), self._in_pre))
        self._in_pre = self._in_pre or tag == "pre"
        if tag == "table":
            source = re.search(r"Source: (\S+\.csv)", self._last_p)
            self._table = ("table", source.group(1) if source else "", [], [])
            self.blocks.append(self._table)
        elif tag == "tr":
            self._row = []
        elif tag in ("td", "th", "li", "p", "h1", "h2", "pre", "figcaption"):
            self._text = ""
        elif tag == "img":
            self.blocks.append(("img", dict(attrs)["src"], dict(attrs).get("alt", "")))

    def handle_data(self, data):
        if self._text is not None:
            self._text += data

    def handle_endtag(self, tag):
        if tag == "pre":
            self._in_pre = False
        if tag in ("table", "h2"):       # a caption names the table right after it only
            self._last_p = ""
        if tag in ("td", "th"):
            self._row.append(self._text.translate(PRINT_SPACES).strip())
            self._text = None
        elif tag == "tr":
            if self._table[2]:
                self._table[3].append(self._row)
            else:
                self._table[2].extend(self._row)
        elif tag in ("li", "p", "h1", "h2", "pre", "figcaption") and self._text is not None:
            text = self._text if tag == "pre" else " ".join(self._text.split())
            self.blocks.append((tag, text))
            if tag == "p":
                self._last_p = text
            self._text = None

    def tables(self):
        return [b[1:] for b in self.blocks if b[0] == "table"]

    def texts(self, kind):
        return [b[1] for b in self.blocks if b[0] == kind]


def rendered_markdown(text):
    """report.md as a Markdown renderer shows it (CommonMark and GitHub's tables), parsed."""
    return Page(MarkdownIt("commonmark").enable("table").render(text))


def significant(text):
    """Significant digits printed in a number's text."""
    mantissa = re.sub(r"[eE].*", "", text.lstrip("-"))
    if "." not in mantissa:
        mantissa = mantissa.rstrip("0")                  # 105630: the zero only places
    return len(mantissa.replace(".", "").lstrip("0"))


def check_number(text, csv_text, factor, digits, where):
    """A printed number is the CSV value / factor rounded to `digits` significant digits (or
    fewer when the rest are zeros); NaN prints as a dash."""
    value = float(csv_text)
    if math.isnan(value):
        assert text == "—", where
        return
    shown, exact = float(text), value / factor
    assert significant(text) <= digits, where
    if exact != 0:
        ulp = 10.0 ** (math.floor(math.log10(abs(exact))) - digits + 1)
        assert abs(shown - exact) <= 0.5 * ulp * (1 + 1e-9), (where, text, exact)
    else:
        assert shown == 0, where


def check_cell(text, csv_text, factor, digits, where):
    try:
        float(csv_text)
    except ValueError:
        assert text == (csv_text or "—") or text == csv_text, (where, text, csv_text)
        return
    check_number(text, csv_text, factor, digits, where)


def split_unit(column):
    match = re.fullmatch(r"(.*?) \[(.*)\]", column)
    return (match.group(1), match.group(2)) if match else (column, "")


def factor(shown_unit, csv_unit):
    """SI per unit shown (1 where the CSV is in that unit already, e.g. [g])."""
    return 1.0 if csv_unit == shown_unit else FACTORS.get(shown_unit, 1.0)
