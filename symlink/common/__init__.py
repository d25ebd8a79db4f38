"""What every layer shares, importing nothing else of symlink: the rule user names follow
(:mod:`~symlink.common.names`), how symbols print (:mod:`~symlink.common.notation`), angle wrapping and units
(:mod:`~symlink.common.angles`), how result records show in a notebook (:mod:`~symlink.common.display`),
atomic files (:mod:`~symlink.common.files`), memory budgets (:mod:`~symlink.common.limits`) and the rounding
tolerance at a toggle (:mod:`~symlink.common.rounding`).

NumPy at most: nothing here imports SymPy.
"""
