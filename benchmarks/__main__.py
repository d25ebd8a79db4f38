"""``python -m benchmarks``: the benchmark's command line (see :mod:`benchmarks.bench`)."""
import sys

from benchmarks.bench import main

if __name__ == "__main__":
    sys.exit(main())
