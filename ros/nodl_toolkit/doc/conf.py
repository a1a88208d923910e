"""Sphinx configuration of the NoDL toolkit's documentation.

Built by ``make docs`` (``sphinx-build -W`` into ``build/docs``) and by rosdoc2 for the
``nodl_toolkit`` package (``rosdoc2 build --package-path ros/nodl_toolkit``), which runs
this file from a copy of this folder.  The verb reference, the file formats, the code
catalogue and the examples' node pages are generated at build time by ``_ext/nodl_sphinx.py``;
the Python API by autodoc.
"""

import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(_HERE, '_ext'))

from nodl_sphinx import repository_root  # noqa: E402

# The library documented is the one of this repository (not an installed copy).
_ROOT = str(repository_root(_HERE))
if _ROOT not in sys.path:
    sys.path.insert(0, _ROOT)

project = 'NoDL toolkit'
author = 'NoDL toolkit maintainers'
copyright = '2025, NoDL toolkit maintainers'  # noqa: A001 - Sphinx's name
release = version = __import__('nodl').__version__

extensions = ['myst_parser', 'sphinx.ext.autodoc', 'nodl_sphinx']
source_suffix = {'.md': 'markdown'}
root_doc = 'index'
exclude_patterns = ['_build', '_ext', 'Thumbs.db', '.DS_Store',
                    # rosdoc2 copies this folder again as user_docs/ into the folder it builds
                    # (this one's copy): the pages are read once, from here.
                    'user_docs']

myst_enable_extensions = ['colon_fence', 'deflist']
myst_heading_anchors = 4
# Quotes stay as typed: commands and options are copied from the pages.
smartquotes = False

autodoc_member_order = 'bysource'
autodoc_typehints = 'description'
autodoc_default_options = {'members': True, 'show-inheritance': True}

html_theme = 'alabaster'
html_title = f'NoDL toolkit {release}'
html_static_path: list[str] = []

# rosdoc2 runs this file and then adds its own settings: no inventory is fetched.
intersphinx_mapping: dict[str, tuple[str, str]] = {}
rosdoc2_settings = {'enable_intersphinx': False, 'automatically_extend_intersphinx_mapping': False}
