"""Render the first two pages of the broad tank example's calc sheet as the PNGs that
docs/python.md ("The calc sheet") shows: calc_sheet_page_1.png and calc_sheet_page_2.png,
beside this file.

Run from the repository:  python docs/make_calc_sheet_pages.py
It needs sloshdyn installed with its 'pdf' extra (WeasyPrint) and poppler's pdftoppm
(bash .ci/dev installs both). The pages are those of data/examples/tank_design.nml's
report.pdf on A4, at 100 dpi; only the date in the title block changes from run to run.
"""

import os
import subprocess
import tempfile
from pathlib import Path

import sloshdyn

HERE = Path(__file__).resolve().parent
EXAMPLE = Path("data") / "examples" / "tank_design.nml"     # as the title block shows it


def main():
    os.chdir(HERE.parent)
    with tempfile.TemporaryDirectory() as scratch:
        sheet = sloshdyn.design_report(EXAMPLE, Path(scratch) / "calc")
        subprocess.run(["pdftoppm", "-r", "100", "-f", "1", "-l", "2", "-png", str(sheet.pdf),
                        str(Path(scratch) / "page")], check=True)
        for k in (1, 2):
            page = next(Path(scratch).glob(f"page-*{k}.png"))
            (HERE / f"calc_sheet_page_{k}.png").write_bytes(page.read_bytes())
            print(HERE / f"calc_sheet_page_{k}.png")


if __name__ == "__main__":
    main()
