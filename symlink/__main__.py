"""``python -m symlink`` is the ``symlink`` command."""
import sys

from .cli import main

sys.exit(main())
