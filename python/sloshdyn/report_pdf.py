"""report.pdf: the calc sheet's HTML laid out on paper by WeasyPrint (the 'pdf' extra; on
Debian it needs Pango, which .ci/dev installs), with the print CSS of report_layout: page
numbers, repeated table headers, the paper size asked for."""

from __future__ import annotations

import logging

from ._extras import require
from ._files import atomic_path


def write_pdf(html_text, path):
    """Render the sheet's HTML (self-contained) into the PDF file `path`, written whole."""
    require("pdf", "weasyprint")
    import weasyprint

    log = logging.getLogger("weasyprint")
    level = log.level
    log.setLevel(logging.ERROR)      # its notes on CSS it does not use are not the user's
    try:
        document = weasyprint.HTML(string=html_text).render()
        with atomic_path(path) as tmp:
            document.write_pdf(tmp)
    finally:
        log.setLevel(level)
