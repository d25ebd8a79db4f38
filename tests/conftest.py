"""Make ``tests/`` importable, so that tests can ``from references import ...``."""

import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
