"""Files and formats: linkage files (:mod:`~symlink.io.linkage_file`), joint tables
(:mod:`~symlink.io.joint_tables`), scenes (:mod:`~symlink.io.scene`), every export
(:mod:`~symlink.io.export`), the generated files of the derivation scripts (:mod:`~symlink.io.derivation`),
verified sweep folders (:mod:`~symlink.io.sweep_folder`), and other tools' descriptions of linkages, read and
written: pylinkage's JSON mechanisms (:mod:`~symlink.io.pylinkage`), Pyslvs's expressions and the Pyslvs-UI
projects that hold them (:mod:`~symlink.io.pyslvs`).

Each reader is a strict grammar of its own (no ``eval``).
"""
