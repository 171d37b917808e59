"""`python -m sloshdyn` and the console script sloshdyn-py: the command line of sloshdyn.cli,
which draws figures, so it needs the 'plot' extra (matplotlib)."""

import sys

from ._errors import exit_code
from ._extras import MissingExtraError


def main(argv=None):
    """Run sloshdyn.cli's main; without matplotlib, an error naming the extra to install."""
    try:
        from .cli import main as cli_main    # the plot extra: an error naming it if missing
    except MissingExtraError as exc:
        from ._shipped import NAMELIST_REFERENCE
        print(f"sloshdyn-py: error: {exc} (the namelist reference, without it: "
              f"{NAMELIST_REFERENCE})", file=sys.stderr)
        return exit_code(exc)
    return cli_main(argv)


# guarded: Dask's worker processes (spawn) import the parent's __main__ module again
if __name__ == "__main__":
    raise SystemExit(main())
