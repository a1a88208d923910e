"""Modules a Python launch file imports that are not installed here, read as placeholders.

Launch files import helpers a ROS machine has and this one may not (``xacro``,
``nav2_common.launch``, ``moveit_configs_utils``...).  While a Python launch file is
evaluated, :class:`MissingModules` sits last on ``sys.meta_path``: a top-level module that
no other finder finds (neither on ``sys.path`` nor in an ament prefix's Python folders),
imported by the launch file itself or by a helper installed in such a folder, imports as
a module of :class:`Placeholder` values, with one NODL513 warning at the import line.
Its submodules import alike; a module that exists but raises stays an error, and a
missing submodule of an installed package stays ``ModuleNotFoundError``.  The stubs leave
``sys.modules`` when the evaluation ends.

A placeholder stands for any value the module would compute: its attributes, calls and
items are placeholders too.  Where it lands it is what only the running launch knows:
a substitution (performed: NODL513, the existing run-time value handling; a node's
parameter entry, ``remappings`` or ``arguments`` given as one: NODL513, the node analysed
without it), an action (NODL512: the nodes it may start are missing).  Python operations
on it go on: ``str()``, an f-string or ``os.path.join`` give a :class:`RunTimeText` (the
marker text ``<WHAT: known at run time>``, which an action or parameter of the stand-ins
reads as a run-time value again, see :func:`run_time`), ``+`` with a string gives such a
text and with a list a list ending with the placeholder; iteration gives nothing (NODL512 at
the loop, once per place: what would be made from its items is missing), unpacking it into a
dict (``{**value}``, ``update()``, ``dict()``) one marker key (:meth:`Placeholder.keys`: in a
node's parameters entry, parameters only the running launch knows), ``len()`` is 0, truth
is true, ``==``/``<``/``in`` are false (``!=`` true), ``with`` works, a class of the launch
file may derive from it (its instances are placeholders); ``int()``/``float()`` raise, as
the value is not known.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import sys
import types
from typing import TYPE_CHECKING, Any

from nodl.launch import actions as A
from nodl.launch import conditions as C
from nodl.launch import substitutions as S
from nodl.launch.errors import Unevaluable
from nodl.launch.model import SourceLocation
from nodl.launch.python_places import frame_location

if TYPE_CHECKING:
    from nodl.launch.context import LaunchContext

__all__ = ['MissingModules', 'Placeholder', 'RunTimeText', 'run_time', 'entities', 'make_placeholder',
           'package_folder', 'stubs_active', 'unpacked']

#: Attribute look-ups from the toolkit's own code (``hasattr(item, 'nodl_parameter')``...)
#: must not be answered with a placeholder: only the launch file's code gets them.
_TOOLKIT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), '')
#: The import system's own frames between an import and the finder (``importlib.util``, which
#: only asks whether a module exists, is not one of them: asking finds no stub).
_IMPORTLIB = frozenset({'<frozen importlib._bootstrap>', '<frozen importlib._bootstrap_external>',
                        importlib.import_module.__code__.co_filename})
_ACTIVE: list[MissingModules] = []  # the evaluation under way (at most one at a time)
_MARK = ': known at run time>'
_LONGEST = 100  # a description longer than this is cut (a long chain of calls)


def stubs_active() -> bool:
    """Whether the evaluation under way gave the launch file a missing module (only then can
    a placeholder or a run-time text exist, so only then are arguments looked through)."""
    return bool(_ACTIVE) and bool(_ACTIVE[-1].stubbed)


def _where() -> SourceLocation:
    if not _ACTIVE:
        return SourceLocation('', 0, 0)
    return frame_location(_ACTIVE[-1].path, sys._getframe(2))


def _short(what: str) -> str:
    # The start names the module, the end what was asked of it: a long chain loses its middle.
    return what if len(what) <= _LONGEST else f'{what[:40]}...{what[3 - _LONGEST + 40:]}'


def make_placeholder(what: str, module: str, missing: str = '') -> Placeholder:
    """A placeholder for ``what`` of the missing ``module``, made where the launch file is
    (``missing``: what the analysis lacks because of it, said with the warning)."""
    value = object.__new__(Placeholder)
    value.__dict__.update(_nodl_what=_short(what), _nodl_module=module, _nodl_missing=missing,
                          location=_where())
    return value


def _derive(parent: Placeholder, what: str) -> Placeholder:
    return make_placeholder(what, parent._nodl_module)


class Placeholder(A.Action, S.Substitution):
    """A value computed by a module that is not installed here (see the module docstring).

    It is an action (executed: a NODL512 warning, the nodes it may start are missing) and
    a substitution (performed: :class:`~nodl.launch.errors.Unevaluable`, NODL513)."""

    _nodl_what = 'a value'
    _nodl_module = '?'
    _nodl_missing = ''

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        # Only an instance of a launch file's class derived from a placeholder gets here.
        self._nodl_what = _short(f'{type(self).__name__}(...) (a class derived from {type(self)._nodl_what})')
        self.location = _where()
        self.condition = kwargs.get('condition')

    def __init_subclass__(cls, **kwargs: Any) -> None:
        # A launch file's class derived from a placeholder stays a placeholder for the walk:
        # what the toolkit calls is this class's, whatever the launch file's class defines.
        super().__init_subclass__(**kwargs)
        for name in ('execute', 'perform', 'describe'):
            if name in cls.__dict__:
                setattr(cls, name, getattr(Placeholder, name))

    # -- what the walk asks ----------------------------------------------------------------
    @property
    def condition(self) -> C.Condition | None:
        """The ``condition`` given to the call that made it, if it is a condition."""
        found: C.Condition | None = self.__dict__.get('_nodl_condition')
        return found

    @condition.setter
    def condition(self, value: Any) -> None:
        if isinstance(value, Placeholder):
            value = C.IfCondition(value)  # evaluated: a run-time value (NODL513)
        self.__dict__['_nodl_condition'] = value if isinstance(value, C.Condition) else None

    def execute(self, context: LaunchContext) -> list[A.Action] | None:
        context.warn('NODL512', f"{self._nodl_what} cannot be evaluated without running the launch "
                                f"(it comes from '{self._nodl_module}', which is not installed here); "
                                'nodes it would start are missing from the analysis', self.location)
        return None

    def perform(self, context: LaunchContext) -> str:
        raise Unevaluable(f"the value of {self._nodl_what} ('{self._nodl_module}' is not installed here) "
                          f'is known only when the launch runs{self._nodl_missing}')

    def describe(self) -> str:
        return self._nodl_what

    # -- what the launch file does with it -------------------------------------------------
    def __getattr__(self, name: str) -> Any:
        asking = sys._getframe(1).f_code.co_filename
        toolkit = asking.startswith(_TOOLKIT) and not (_ACTIVE and asking == _ACTIVE[-1].path)
        if name.startswith('__') or toolkit:
            raise AttributeError(name)
        return _derive(self, f'{self._nodl_what}.{name}')

    def __call__(self, *args: Any, **kwargs: Any) -> Placeholder:
        made = _derive(self, f"{self._nodl_what}({'...' if args or kwargs else ''})")
        made.condition = kwargs.get('condition')  # a condition launch would honour
        return made

    def __getitem__(self, key: Any) -> Placeholder:
        return _derive(self, f'{self._nodl_what}[...]')

    def __setitem__(self, key: Any, value: Any) -> None:
        return None

    def __delitem__(self, key: Any) -> None:
        return None

    def keys(self) -> list[RunTimeText]:
        """``{**value}``, ``dict.update(value)``, ``dict(value)``: one marker key, the text of a
        placeholder standing for the entries only the running launch knows (a node's
        ``parameters`` entry reads it as such: :func:`unpacked`); its item is a placeholder."""
        entries = _derive(self, f'the entries of {self._nodl_what}')
        entries.__dict__['_nodl_entries'] = True
        return [entries._text()]

    def __iter__(self) -> Any:
        # Its items are not known: it iterates as nothing, and the launch file's loop over it
        # makes nothing, which is said once per place (a loop of nodes would vanish unsaid).
        if _ACTIVE:
            _ACTIVE[-1].iterated(self, _where())
        return iter(())

    def __len__(self) -> int:
        return 0

    def __bool__(self) -> bool:
        return True

    def __contains__(self, item: Any) -> bool:
        return False

    def __eq__(self, other: object) -> bool:
        return self is other

    def __ne__(self, other: object) -> bool:
        return self is not other

    def __lt__(self, other: Any) -> bool:
        return False

    __le__ = __gt__ = __ge__ = __lt__

    def __hash__(self) -> int:
        return id(self)

    def __enter__(self) -> Placeholder:
        return self

    def __exit__(self, *exc: Any) -> None:
        return None  # an exception in the block goes on

    def _text(self) -> RunTimeText:
        text = f'<{self._nodl_what}{_MARK}'
        if _ACTIVE:
            _ACTIVE[-1].markers.setdefault(text, self)
        return RunTimeText(text, self)

    def __str__(self) -> str:
        return self._text()

    def __format__(self, spec: str) -> str:
        return self._text()

    def __fspath__(self) -> str:
        return self._text()

    def __add__(self, other: Any) -> Any:
        if isinstance(other, str):
            return self._text() + other
        if type(other) in (list, tuple):
            return type(other)((self, *other))
        return _derive(self, f'{self._nodl_what} + ...')

    def __radd__(self, other: Any) -> Any:
        if isinstance(other, str):
            return other + self._text()
        if type(other) in (list, tuple):
            return type(other)((*other, self))
        return _derive(self, f'... + {self._nodl_what}')

    def _operation(self, *other: Any) -> Placeholder:
        return _derive(self, f'an expression with {self._nodl_what}')

    __sub__ = __rsub__ = __mul__ = __rmul__ = __truediv__ = __rtruediv__ = _operation
    __floordiv__ = __rfloordiv__ = __mod__ = __rmod__ = __pow__ = __rpow__ = _operation
    __and__ = __rand__ = __or__ = __ror__ = __xor__ = __rxor__ = _operation
    __neg__ = __pos__ = __abs__ = __invert__ = _operation

    def _number(self) -> Any:
        raise TypeError(f"{self._nodl_what} comes from '{self._nodl_module}', which is not installed "
                        'here: its number is known only when the launch runs')

    __int__ = __float__ = __index__ = __complex__ = _number

    def __instancecheck__(self, instance: Any) -> bool:
        return False

    def __subclasscheck__(self, subclass: Any) -> bool:
        return False

    def __mro_entries__(self, bases: Any) -> tuple[type, ...]:
        # class Bridge(ros_gz_bridge.actions.RosGzBridge): ... derives from a class of
        # placeholders, whose instances are placeholders (actions, substitutions).
        name = self._nodl_what.rpartition('.')[2] or 'Placeholder'
        return (type(name, (Placeholder,), {'_nodl_what': self._nodl_what,
                                            '_nodl_module': self._nodl_module}),)


class RunTimeText(str):
    """A text made from a placeholder (``str()``, an f-string, ``os.path.join``): its
    marker text, remembering the placeholder; ``+`` with a text keeps it a run-time text."""

    placeholder: Placeholder

    def __new__(cls, text: str, placeholder: Placeholder) -> RunTimeText:
        made = super().__new__(cls, text)
        made.placeholder = placeholder
        return made

    def __getnewargs__(self) -> tuple[str, Placeholder]:  # type: ignore[override]
        return str.__str__(self), self.placeholder  # copied, it keeps its placeholder

    def __add__(self, other: Any) -> Any:
        if not isinstance(other, str):
            return NotImplemented
        return RunTimeText(str.__add__(self, other), self.placeholder)

    def __radd__(self, other: Any) -> Any:
        if not isinstance(other, str):
            return NotImplemented
        return RunTimeText(str.__add__(other, self), self.placeholder)


def _keeps_run_time(name: str) -> Any:
    """A ``str`` method of :class:`RunTimeText` whose text result stays a run-time text
    (``.upper()``, ``.replace()``, ``%``...: the value it stands for is still unknown)."""
    method = getattr(str, name)

    def kept(self: RunTimeText, *args: Any, **kwargs: Any) -> Any:
        result = method(self, *args, **kwargs)
        if isinstance(result, str):
            return RunTimeText(result, self.placeholder)
        if isinstance(result, (list, tuple)):
            return type(result)(RunTimeText(r, self.placeholder) if isinstance(r, str) else r
                                for r in result)
        return result
    kept.__name__ = name
    return kept


for _name in ('upper', 'lower', 'casefold', 'capitalize', 'title', 'swapcase', 'strip', 'lstrip',
              'rstrip', 'replace', 'format', 'format_map', 'center', 'ljust', 'rjust', 'zfill',
              'expandtabs', 'removeprefix', 'removesuffix', 'split', 'rsplit', 'partition',
              'rpartition', 'splitlines', '__mod__', '__mul__', '__rmul__', '__getitem__'):
    setattr(RunTimeText, _name, _keeps_run_time(_name))


def _text_value(text: str, placeholder: Placeholder | None) -> Any:
    """The run-time value a text made from a placeholder stands for."""
    if placeholder is None and _ACTIVE:
        placeholder = next((p for marker, p in _ACTIVE[-1].markers.items() if marker in text), None)
    if placeholder is None:
        return text
    if text == f'<{placeholder._nodl_what}{_MARK}':
        return placeholder
    made = make_placeholder(f'a text with {placeholder._nodl_what}', placeholder._nodl_module)
    made.location = placeholder.location
    return made


def run_time(value: Any, depth: int = 0) -> Any:
    """``value`` with every text made from a placeholder (in lists, tuples and dicts too)
    replaced by a placeholder: a run-time value for the stand-ins (a substitution).
    ``value`` itself when there is none, or when no module is stubbed."""
    if not _ACTIVE or not _ACTIVE[-1].markers or depth > 20:
        return value
    kind = type(value)
    if kind is RunTimeText:
        return _text_value(value, value.placeholder)
    if kind is str:  # (made from a run-time text by code that lost its type: ''.join...)
        return _text_value(value, None) if _MARK in value.lower() else value
    if kind in (list, tuple):
        items = [run_time(v, depth + 1) for v in value]
        return kind(items) if any(a is not b for a, b in zip(items, value, strict=True)) else value
    if kind is dict:
        pairs = [(run_time(k, depth + 1), run_time(v, depth + 1)) for k, v in value.items()]
        changed = any(a is not b or c is not d for (a, c), (b, d) in zip(pairs, value.items(), strict=True))
        return dict(pairs) if changed else value
    return value


def unpacked(name: Any) -> Placeholder | None:
    """The placeholder a parameter name (a substitution or a list of them) holds that stands
    for the entries of a placeholder unpacked into the dict (``{**value}``: see
    :meth:`Placeholder.keys`), if any."""
    for part in name if isinstance(name, list) else [name]:
        if isinstance(part, Placeholder) and part.__dict__.get('_nodl_entries'):
            return part
    return None


def entities(value: Any) -> Any:
    """What a launch file gives as a list of actions: a placeholder is one (unknown) action."""
    return [value] if isinstance(value, Placeholder) else value


def package_folder(package: Placeholder | RunTimeText) -> str:
    """``get_package_share_directory(package)`` (or the prefix) of a package named by a
    placeholder: a run-time text."""
    source = package if isinstance(package, Placeholder) else package.placeholder
    return str(make_placeholder(f'the folder of the package {source._nodl_what}', source._nodl_module))


class MissingModules:
    """The finder, last on ``sys.meta_path`` while one launch file is evaluated, that gives
    a module found nowhere else as a module of placeholders (see the module docstring).

    A meta path finder and loader by protocol (``find_spec``, ``create_module``,
    ``exec_module``): importlib.abc's base classes would load importlib.resources, tempfile
    and random into ``nodl analyse`` for nothing."""

    def __init__(self, context: LaunchContext, path: str, helper_roots: list[str]) -> None:
        self.context = context
        self.path = path
        self.helper_roots = tuple(os.path.join(p, '') for p in helper_roots)
        #: The top-level modules given as placeholders, in the order they were imported.
        self.stubbed: list[str] = []
        self.created: list[str] = []
        self.markers: dict[str, Placeholder] = {}
        self._iterated: set[SourceLocation] = set()  # where a placeholder was iterated (said once)

    def __enter__(self) -> MissingModules:
        sys.meta_path.append(self)
        _ACTIVE.append(self)
        return self

    def __exit__(self, *exc: Any) -> None:
        _ACTIVE.remove(self)
        sys.meta_path.remove(self)
        for name in self.created:  # the stubs never outlive the evaluation
            module = sys.modules.get(name)
            if isinstance(module, _StubModule):
                del sys.modules[name]
        self.markers.clear()

    def iterated(self, value: Placeholder, where: SourceLocation) -> None:
        """A NODL512 warning, once per place, that ``value`` was iterated as nothing."""
        if where in self._iterated:
            return
        self._iterated.add(where)
        self.context.warn('NODL512', f"{value._nodl_what} is iterated, but its items are known only when "
                          f"the launch runs (it comes from '{value._nodl_module}', which is not installed "
                          'here): it is taken as empty, and what would be made from its items (nodes, '
                          'parameters, arguments...) is missing from the analysis', where)

    def _importer(self) -> tuple[SourceLocation, str] | None:
        """Where the launch file imports, and the helper file importing if not the launch
        file itself; None when the import comes from elsewhere (a library keeps its
        ``ImportError`` for an optional module)."""
        frame: Any = sys._getframe(2)
        while frame is not None and frame.f_code.co_filename in _IMPORTLIB:
            frame = frame.f_back
        if frame is None:
            return None
        filename = frame.f_code.co_filename
        if filename == self.path:
            return frame_location(self.path, frame), ''
        if filename.startswith(self.helper_roots):
            return frame_location(self.path, frame), filename
        return None

    def find_spec(self, fullname: str, path: Any, target: Any = None) -> Any:
        """A spec for a top-level module found nowhere else (or a submodule of a stub)."""
        top = fullname.partition('.')[0]
        if top not in self.stubbed:
            if '.' in fullname:
                return None  # a submodule missing from an installed package stays an error
            importer = self._importer()
            if importer is None:
                return None
            where, helper = importer
            self.stubbed.append(top)
            through = f' (through {helper})' if helper else ''
            self.context.warn('NODL513', f"the Python launch file imports '{top}'{through}, which is not "
                              'installed here (neither on the Python path nor in the Python folders of '
                              'an ament prefix): what it computes is known only when the launch runs '
                              '(install or source the package that provides it to analyse it)', where)
        return importlib.util.spec_from_loader(fullname, self, is_package=True)  # type: ignore[arg-type]  # (exec_module, not load_module)

    def create_module(self, spec: Any) -> types.ModuleType:
        """A module whose every attribute is a placeholder."""
        self.created.append(spec.name)
        return _StubModule(spec.name, spec.name.partition('.')[0])

    def exec_module(self, module: types.ModuleType) -> None:
        """Nothing to run."""
        return None


class _StubModule(types.ModuleType):
    def __init__(self, name: str, top: str) -> None:
        super().__init__(name)
        self.__path__: list[str] = []  # a package: its submodules import
        self._nodl_top = top

    def __getattr__(self, name: str) -> Any:
        if name.startswith('__'):
            raise AttributeError(name)
        return make_placeholder(f'{self.__name__}.{name}', self._nodl_top)
