"""Other tools' descriptions of linkages, read and written: pylinkage's JSON mechanisms, Pyslvs's expressions
(and the Pyslvs-UI projects that hold them).

Each reader is a strict grammar of its own (no ``eval``) that returns a
:class:`~symlink.joints.JointDescription`; ``.build()`` gives the linkage
(:func:`symlink.joints.from_joints`), and :func:`symlink.joint_tables.joint_file_text`
(by joints) or :func:`symlink.linkage_file.linkage_text` (by vectors and loops) write
symlink's own linkage file from it.  Each writer takes what
:func:`~symlink.joints.from_joints` returns.
"""
from .pylinkage import read_pylinkage, write_pylinkage
from .pyslvs import pyslvs_inputs, read_pyslvs, read_pyslvs_project, write_pyslvs

__all__ = ["read_pylinkage", "write_pylinkage", "read_pyslvs", "read_pyslvs_project", "write_pyslvs", "pyslvs_inputs"]
