"""``nodl doc``: reference pages for nodes, packages and launched systems.

A consumer of the shared layers (it imports no other consumer):

* :mod:`.model`: the content of a page, from a resolved node, a package's
  registrations or an analysed system: tables of words, no markup;
* :mod:`.collect`: the command line's targets (a definition file,
  ``PACKAGE``, ``PACKAGE/EXECUTABLE``, a definitions folder, a launch file)
  -> the pages of one run (:class:`~nodl.doc.collect.DocSet`);
* :mod:`.markdown` (MyST), :mod:`.html` (self-contained), :mod:`.rst`: the
  renderers, each escaping every name and description for its format;
* :mod:`.writer`: the rendered files written under the output folder
  (marked, atomic, never over a file the user wrote);
* :mod:`.check`: the rendered files compared with those on disk (``--check``).
"""

from __future__ import annotations

__all__ = ['FORMATS', 'EXTENSIONS']

#: The output formats.
FORMATS = ('md', 'html', 'rst')
#: Format -> the file name ending of its pages.
EXTENSIONS = {'md': '.md', 'html': '.html', 'rst': '.rst'}
