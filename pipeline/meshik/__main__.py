"""`python -m meshik ...`: the `meshik` command (meshik.cli)."""
import sys

from meshik.cli import main

# The guard keeps processes started by multiprocessing's spawn (Dask's workers) from running it again.
if __name__ == "__main__":
    sys.exit(main())
