"""The files shipped with the package for users of the wheel, who have no source checkout: the
example inputs of data/examples (with their records) and the namelist reference
(docs/namelist.md), installed under sloshdyn/examples and sloshdyn/reference."""

from __future__ import annotations

import shutil
from pathlib import Path

from ._errors import FileError

#: the example inputs (*.nml) and their records (records/*.AT2)
EXAMPLES = Path(__file__).parent / "examples"
#: every namelist group and variable, with its default and range
NAMELIST_REFERENCE = Path(__file__).parent / "reference" / "namelist.md"


def copy_examples(directory) -> list[Path]:
    """Copy the example inputs and their records into `directory` (created if missing); a file
    already there is never overwritten (FileError naming it, nothing copied). Returns the
    inputs copied. Their records are found beside them (records/), as in data/examples."""
    directory = Path(directory)
    files = sorted(p.relative_to(EXAMPLES) for p in EXAMPLES.rglob("*")
                   if p.is_file() and p.suffix in (".nml", ".AT2"))
    taken = [str(f) for f in files if (directory / f).exists() or (directory / f).is_symlink()]
    if taken:
        raise FileError(f"{directory}: {', '.join(taken[:5])} already there; nothing copied "
                        "(give a new or empty directory)")
    try:
        for f in files:
            (directory / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(EXAMPLES / f, directory / f)
    except OSError as exc:
        raise FileError(f"cannot copy the examples into {directory}: "
                        f"{exc.strerror or exc}") from None
    return [directory / f for f in files if f.suffix == ".nml"]
