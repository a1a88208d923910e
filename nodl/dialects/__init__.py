"""Dialects: files users already have, converted to NoDL v2 and written from it.

Reading them is the frontends' work (:mod:`nodl.frontends.builtin`: the
``include`` and ``genparamlib`` frontends, by content, never by file name);
this package converts a dialect file into NoDL v2 files
(:mod:`nodl.dialects.convert`, ``nodl convert --from``) and writes NoDL as a
generate_parameter_library file (:mod:`nodl.dialects.export`,
:mod:`nodl.dialects.genparamlib`, ``nodl export genparamlib``).  The dialect
names and :func:`recognise` are the frontends', named here for the converters.
(Legacy XML has its own converter: :mod:`nodl.legacy`.)
"""

from __future__ import annotations

from nodl.frontends.builtin import DIALECTS, GENPARAMLIB, INCLUDE, recognise

__all__ = ['DIALECTS', 'GENPARAMLIB', 'INCLUDE', 'recognise']
