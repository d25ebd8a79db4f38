"""Evaluation: solvers with checked arguments (:mod:`~symlink.numeric.solver`), the compiled C backend
(:mod:`~symlink.numeric.compiled`, :mod:`~symlink.numeric.compiled_library`), the scene cache
(:mod:`~symlink.numeric.cache`) and the solver run from it without SymPy (:mod:`~symlink.numeric.cached_solver`),
results and units, reachable ranges and toggles (:mod:`~symlink.numeric.reachability`), design Jacobians and
the assemblies of a numeric linkage.
"""
