"""From a design to the workshop: tolerance stack-ups and Monte Carlo builds
(:mod:`~symlink.workshop.tolerance`), the links as parts to cut (:mod:`~symlink.workshop.fabrication`) and design
sweeps on Dask (:mod:`~symlink.workshop.sweep`).
"""
