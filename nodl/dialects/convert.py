"""Converting dialect files to NoDL v2 files (what ``nodl convert`` does for YAML/JSON input).

* an ``include``-dialect node document becomes a node definition with
  ``base``, ``mixins`` and ``main``, written under its own file name;
* a generate_parameter_library file becomes an interface definition
  ``<namespace>.nodl.yaml`` whose parameters are the leaves under dotted names.

Nothing is written for an input with errors.  Diagnostics are placed in the
input file.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

from nodl.diagnostics import Diagnostic, Severity, has_errors
from nodl.dialects import INCLUDE, recognise
from nodl.legacy.convert import FileConversion

#: A local include the converted file cannot reach from where it is written.
_UNREACHABLE = 'NODL854'

__all__ = ['DialectConversion', 'FileConversion', 'convert_dialect', 'convert_dialect_file']


class DialectConversion:
    """One input read in a dialect: the NoDL v2 document to write, or the errors."""

    def __init__(self, path: str, dialect: str | None, file_name: str | None,
                 data: dict[str, Any] | None, diagnostics: list[Diagnostic], header: str = '') -> None:
        self.path = path
        #: ``include``, ``genparamlib`` or None (not a dialect file).
        self.dialect = dialect
        #: The name of the file to write (in the output directory).
        self.file_name = file_name
        #: The NoDL v2 document (None if nothing can be written).
        self.data = data
        #: Placed diagnostics, in source order.
        self.diagnostics = diagnostics
        self.header = header

    def text(self) -> str:
        """The NoDL v2 file: a comment saying where it came from, then the document."""
        from nodl.loading import dump_nodl
        from nodl.text_safety import one_line

        assert self.data is not None
        comment = ''.join(f'# {one_line(line)}\n' for line in self.header.splitlines())
        return comment + dump_nodl(self.data)


def _rebase(reference: str, source_dir: str, out_dir: str) -> str:
    """A relative mixin path of the input, relative to the output directory instead."""
    from nodl.composition.resolvers import scheme_of

    if scheme_of(reference) != 'file' or os.path.isabs(reference):
        return reference
    target = os.path.normpath(os.path.join(source_dir, reference))
    return os.path.relpath(target, out_dir).replace(os.sep, '/')


def _unreachable(mixins: list[Any], out_dir: str, original_path: Any) -> list[Diagnostic]:
    """Warnings for local includes the converted file, written into ``out_dir``, cannot reach.

    A relative mixin path may not leave the package of the node file (see the ``file``
    resolver): written outside the source package, the rebased path would.
    """
    from nodl.composition.resolvers import package_root, scheme_of

    boundary = os.path.realpath(package_root(out_dir) or out_dir)
    found: list[Diagnostic] = []
    for index, mixin in enumerate(mixins):
        if not isinstance(mixin, str) or scheme_of(mixin) != 'file' or os.path.isabs(mixin):
            continue
        target = os.path.realpath(os.path.join(out_dir, mixin))
        if os.path.commonpath([boundary, target]) != boundary:
            found.append(Diagnostic(
                Severity.WARNING, f'the converted file, written into {out_dir}, cannot use this local '
                f'include ({target}): a mixin path may not leave its package; write the output inside '
                'the source package, or copy the file along and fix the path',
                original_path(('mixins', index)), code=_UNREACHABLE))
    return found


def convert_dialect(path: str, dialect: str | None = None, out_dir: str | None = None
                    ) -> DialectConversion:
    """Read ``path`` in ``dialect`` (default: recognised by content) as NoDL v2.

    ``out_dir`` is where the result will be written: relative mixin paths
    are rewritten relative to it.  OSError propagates for an unreadable file.
    """
    from pathlib import Path

    from nodl.frontends.source import read_source
    from nodl.frontends.yaml_json import parse_document
    from nodl.validation import validate_data
    from nodl.validation.kinds import Kind

    text, problem = read_source(Path(path), path)
    if text is None:
        assert problem is not None
        return DialectConversion(path, dialect, None, None, [problem])
    parsed = parse_document(text)
    if parsed.diagnostics:
        return DialectConversion(path, dialect, None, None, list(parsed.diagnostics))
    found = recognise(parsed.data)
    wanted = dialect or found
    if wanted is None:
        from nodl.validation.kinds import detect_kind

        what = (f'already a NoDL v2 {detect_kind(parsed.data)} definition; there is nothing to convert'
                if isinstance(parsed.data, dict) and 'nodl_version' in parsed.data else
                'not in a format nodl convert reads (legacy XML, the include dialect, '
                'generate_parameter_library)')
        return DialectConversion(path, None, None, None, [
            Diagnostic(Severity.ERROR, f'{path} is {what}', (), path, 1, 1)])
    if found != wanted:
        from nodl.dialects import DIALECTS

        return DialectConversion(path, wanted, None, None, [Diagnostic(
            Severity.ERROR, f'{path} is not {DIALECTS[wanted]}' +
            (f'; it looks like {DIALECTS[found]} (leave --from out)' if found else ''), (), path, 1, 1)])
    source_dir = os.path.dirname(os.path.abspath(path))
    if wanted == INCLUDE:
        from nodl.frontends.include import read_include
        from nodl.frontends.include import remapped as remapped_include

        reading = read_include(parsed.data)
        document = remapped_include(parsed, reading)
        data = reading.data
        # The dialect warning tells users to convert: that is being done.
        own = [d for d in reading.diagnostics if d.code != 'NODL851']
        checks = validate_data(data, Kind.NODE)
        if out_dir is not None and 'mixins' in data:
            data['mixins'] = [_rebase(m, source_dir, os.path.abspath(out_dir)) if isinstance(m, str)
                              else m for m in data['mixins']]
            own += _unreachable(data['mixins'], os.path.abspath(out_dir), reading.original_path)
        file_name = os.path.basename(path)
        header = (f'Converted by nodl convert from {os.path.basename(path)} (the reference '
                  f"implementation's '{reading.key}' dialect).")
    else:
        from nodl.frontends.genparamlib import read_genparamlib, remapped

        greading = read_genparamlib(parsed.data)
        document = remapped(parsed, greading)
        data = greading.data
        own = list(greading.diagnostics)
        checks = validate_data(data, Kind.INTERFACE)
        file_name = f'{greading.namespace}.nodl.yaml'
        header = (f'Converted by nodl convert from {os.path.basename(path)} (generate_parameter_library, '
                  f"namespace '{greading.namespace}').\n"
                  f'Write it back with: nodl export genparamlib {file_name} -o FILE')
    placed = [parsed.place(d) for d in own] + [document.place(d) for d in checks]
    placed.sort(key=lambda d: (d.line, d.column))
    if has_errors(placed):
        return DialectConversion(path, wanted, file_name, None, placed)
    return DialectConversion(path, wanted, file_name, data, placed, header)


def convert_dialect_file(path: str, out_dir: str, dialect: str | None = None, *,
                         force: bool = False, inputs: Sequence[str] = ()
                         ) -> tuple[FileConversion, str | None]:
    """Convert ``path`` and write the result into ``out_dir`` (nothing on errors).

    Returns the outcome and the dialect the input was read in.  Never raises
    for bad input: an unreadable input is a :class:`FileConversion` with a
    ``problem``; an output that cannot be written or replaced (it is ``path``
    or one of ``inputs``: NODL033; a file nodl did not write, or an edited
    one, unless ``force``: NODL031/NODL032; a failed write: NODL030) is one
    with an empty ``problem`` and that diagnostic last.  The output is written
    atomically, with a content marker (:mod:`nodl.writing`).
    """
    from nodl.writing import WriteError, check_within, output_is_input, write_marked

    try:
        conversion = convert_dialect(path, dialect, out_dir)
    except OSError as exc:
        from nodl.files import describe_os_error

        return FileConversion(path, problem=describe_os_error(exc).lower()), dialect
    if conversion.data is None or conversion.file_name is None:
        return FileConversion(path, [], conversion.diagnostics), conversion.dialect
    target = os.path.join(out_dir, conversion.file_name)
    try:
        clash = check_within(target, out_dir) or output_is_input(target, [path, *inputs], '-o')
        if clash is not None:
            raise WriteError(clash)
        write_marked(target, conversion.text(), force=force, make_parents=True, within=out_dir)
    except WriteError as exc:
        return FileConversion(path, [], conversion.diagnostics + [exc.diagnostic], ''), \
            conversion.dialect
    return FileConversion(path, [target], conversion.diagnostics), conversion.dialect
