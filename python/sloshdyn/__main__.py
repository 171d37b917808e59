from .cli import main

# guarded: Dask's worker processes (spawn) import the parent's __main__ module again
if __name__ == "__main__":
    raise SystemExit(main())
