"""symlink's benchmark and its hand-written baselines, kept outside the runtime package.

Run from a source checkout: ``python -m benchmarks --quick`` (or ``symlink bench --quick``).
"""
