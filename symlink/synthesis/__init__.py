"""Synthesis: find the linkage that does a job.

:mod:`symlink.synthesis.quick_return` designs a quick-return crank-rocker exactly
from its time ratio and stroke; :mod:`symlink.synthesis.motion` guides a coupler through
given poses (motion generation by Burmester theory).
"""
