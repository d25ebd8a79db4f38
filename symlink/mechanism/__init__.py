"""A linkage as a mechanism: its rigid bodies and joints (:mod:`~symlink.mechanism.bodies`), its structure
(:mod:`~symlink.mechanism.topology`, :mod:`~symlink.mechanism.mobility`), linkages described by their joints
(:mod:`~symlink.mechanism.joints`), the atlas of one-DOF chains (:mod:`~symlink.mechanism.atlas`) and the catalog of
ready-made linkages (:mod:`~symlink.mechanism.catalog`), each defined once.
"""
