"""Legacy NoDL (the XML formats of specs 000, 001 and 002) and its conversion to NoDL v2.

Reading is done by :mod:`nodl.frontends.legacy_xml`; converting, by
:mod:`nodl.legacy.convert`::

    from nodl.frontends.legacy_xml import parse_legacy_xml
    from nodl.legacy import convert_legacy, convert_file

    for converted in convert_legacy(parse_legacy_xml(pathlib.Path('pkg.nodl.xml'))):
        converted.file_name, converted.data, converted.diagnostics

    written, diagnostics = convert_file('pkg.nodl.xml', 'out/')

Each :class:`Converted` carries ``origins``, where every path of its v2 data
came from in the XML file; :mod:`nodl.legacy.converted_document` checks the
converted node with it, so a registered legacy node's diagnostics and entity
locations point into the XML file.
"""

from __future__ import annotations

from nodl.legacy.convert import (
    Converted,
    FileConversion,
    convert_file,
    convert_files,
    convert_legacy,
    render_converted,
    seconds_to_ns,
)

__all__ = ['Converted', 'FileConversion', 'convert_file', 'convert_files', 'convert_legacy',
           'render_converted', 'seconds_to_ns']
