"""symlink's version, in a module that imports nothing, so that any module can name it without a cycle."""

__version__ = "0.1.0"
