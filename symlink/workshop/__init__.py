"""From a design to the workshop: tolerance stack-ups (:mod:`~symlink.workshop.tolerance`), the pins' play
(:mod:`~symlink.workshop.pin_play`) and Monte Carlo builds (:mod:`~symlink.workshop.sampled_builds`), the links as
parts to cut (:mod:`~symlink.workshop.fabrication`) and design sweeps on Dask (:mod:`~symlink.workshop.sweep`).
"""
