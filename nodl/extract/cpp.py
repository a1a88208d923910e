"""The rclcpp extractor: a node's interface from C++ source, read with tree-sitter-cpp.

Nothing is compiled or run.  The sources of a package are parsed with the tree-sitter C++
grammar (the ``extract`` extra: ``tree-sitter`` and ``tree-sitter-cpp``), and the calls an
``rclcpp::Node`` / ``rclcpp_lifecycle::LifecycleNode`` (or ``nav2_util::LifecycleNode``) makes
are read: ``create_publisher`` / ``create_subscription`` / ``create_service`` /
``create_client``, ``create_generic_publisher`` / ``create_generic_subscription``,
``rclcpp_action::create_server`` / ``create_client``, ``declare_parameter`` (with its default
and its ParameterDescriptor's ``read_only``, description and ranges), ``declare_parameters``
with a map of defaults, and the helpers real nodes use (tf2_ros broadcasters and listeners,
diagnostic_updater, message_filters subscribers; image_transport's topics are gaps).

What the source does not fix before it runs is never guessed: a name, type, QoS or default
that is not a compile-time constant is a :class:`~nodl.extract.model.Gap` with its
place (``topic name at talker.cpp:42:31 is computed at run time``).  Constants are resolved:
string and number literals, adjacent string literals, ``+`` of strings, ``const`` /
``constexpr`` / ``static const std::string`` variables, ``#define`` of a literal, and members
initialised from literals (in their declaration or a constructor's initialiser list) and
never assigned again.  A name that is the value of a declared parameter is a gap that says
which parameter.

Input problems are one located diagnostic each, never an exception: a file that cannot be
read, is too large, is generated, does not parse (the first place the parser gave up), a
``#define`` whose body creates entities, a template parameter used as a type.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.extract.model import PARAMETERS, ExtractedEntity, ExtractedNode, Extraction, Gap
from nodl.location import Location
from nodl.vocabulary import ROS_PARAMETER_TYPE_NAMES

if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any

    from nodl.extract.cmake import CMakeTargets
    from nodl.model.qos import QoSProfile

__all__ = ['CPP_SUFFIXES', 'MAX_FILE_BYTES', 'cpp_parser', 'extract_cpp', 'extract_cpp_package',
           'qos_of_name']

#: File name endings read as C++ sources and headers.
CPP_SUFFIXES = ('.cpp', '.cc', '.cxx', '.c++', '.hpp', '.hh', '.hxx', '.h', '.ipp')
#: A file larger than this is not read (NODL932): hand-written node sources are far smaller.
MAX_FILE_BYTES = 2 * 1024 * 1024

_NOT_INSTALLED = 'NODL930'
_UNREADABLE = 'NODL931'
_TOO_LARGE = 'NODL932'
_GENERATED = 'NODL933'
_SYNTAX = 'NODL934'
_MACRO = 'NODL935'
_TEMPLATE = 'NODL936'
_NAME = 'NODL937'
_TYPE = 'NODL938'
_QOS = 'NODL939'
_DEFAULT = 'NODL940'
_PARAM_NAME = 'NODL941'
_PLUGIN = 'NODL942'
_NODE_NAME = 'NODL943'
_UNTIED = 'NODL944'

_NODE_BASES = {
    'rclcpp::Node': 'node', 'Node': 'node',
    'rclcpp_lifecycle::LifecycleNode': 'lifecycle_node', 'LifecycleNode': 'lifecycle_node',
    'nav2_util::LifecycleNode': 'lifecycle_node', 'nav2::LifecycleNode': 'lifecycle_node',
}
_GENERATED_MARK = re.compile(rb'@generated|(auto-?)?generated\b.{0,80}\b(do not|don\'t|never) edit',
                             re.IGNORECASE | re.DOTALL)
_ENTITY_CALLS = ('create_publisher', 'create_subscription', 'create_service', 'create_client',
                 'create_generic_publisher', 'create_generic_subscription', 'declare_parameter',
                 'declare_parameters', 'create_server')

# ----------------------------------------------------------------------------- QoS

#: rmw's and rclcpp's named profiles, expanded to their policies (rmw/qos_profiles.h,
#: rclcpp/qos.hpp).  Values: (history, depth, reliability, durability, lifespan_ns).
_PROFILES: dict[str, tuple[str, int | None, str, str, int | None]] = {
    'rmw_qos_profile_sensor_data': ('KEEP_LAST', 5, 'BEST_EFFORT', 'VOLATILE', None),
    'rmw_qos_profile_parameters': ('KEEP_LAST', 1000, 'RELIABLE', 'VOLATILE', None),
    'rmw_qos_profile_default': ('KEEP_LAST', 10, 'RELIABLE', 'VOLATILE', None),
    'rmw_qos_profile_services_default': ('KEEP_LAST', 10, 'RELIABLE', 'VOLATILE', None),
    'rmw_qos_profile_parameter_events': ('KEEP_LAST', 1000, 'RELIABLE', 'VOLATILE', None),
    'rmw_qos_profile_system_default': ('SYSTEM_DEFAULT', None, 'SYSTEM_DEFAULT', 'SYSTEM_DEFAULT', None),
    'rmw_qos_profile_best_available': ('KEEP_LAST', 10, 'BEST_AVAILABLE', 'BEST_AVAILABLE', None),
    'rmw_qos_profile_rosout_default': ('KEEP_LAST', 1000, 'RELIABLE', 'TRANSIENT_LOCAL', 10_000_000_000),
    'SensorDataQoS': ('KEEP_LAST', 5, 'BEST_EFFORT', 'VOLATILE', None),
    'ParametersQoS': ('KEEP_LAST', 1000, 'RELIABLE', 'VOLATILE', None),
    'ServicesQoS': ('KEEP_LAST', 10, 'RELIABLE', 'VOLATILE', None),
    'ParameterEventsQoS': ('KEEP_LAST', 1000, 'RELIABLE', 'VOLATILE', None),
    'RosoutQoS': ('KEEP_LAST', 1000, 'RELIABLE', 'TRANSIENT_LOCAL', 10_000_000_000),
    'SystemDefaultsQoS': ('SYSTEM_DEFAULT', None, 'SYSTEM_DEFAULT', 'SYSTEM_DEFAULT', None),
    'ClockQoS': ('KEEP_LAST', 1, 'BEST_EFFORT', 'VOLATILE', None),
    'BestAvailableQoS': ('KEEP_LAST', 10, 'BEST_AVAILABLE', 'BEST_AVAILABLE', None),
}
_POLICY_WORDS = {
    'reliable': 'RELIABLE', 'best_effort': 'BEST_EFFORT', 'system_default': 'SYSTEM_DEFAULT',
    'best_available': 'BEST_AVAILABLE', 'transient_local': 'TRANSIENT_LOCAL', 'volatile': 'VOLATILE',
    'keep_last': 'KEEP_LAST', 'keep_all': 'KEEP_ALL', 'automatic': 'AUTOMATIC',
    'manual_by_topic': 'MANUAL_BY_TOPIC',
}


def qos_of_name(name: str) -> QoSProfile | None:
    """The profile a named QoS stands for (``rclcpp::SensorDataQoS``,
    ``rmw_qos_profile_sensor_data``...), None for a name that is not one."""
    from nodl.model.qos import QoSProfile

    short = name.rsplit('::', 1)[-1]
    if short not in _PROFILES:
        return None
    history, depth, reliability, durability, lifespan = _PROFILES[short]
    return QoSProfile(history=history, depth=depth, reliability=reliability,
                      durability=durability, lifespan_ns=lifespan)


def _depth_qos(depth: int) -> QoSProfile:
    from nodl.model.qos import QoSProfile

    return QoSProfile(history='KEEP_LAST', depth=depth, reliability='RELIABLE', durability='VOLATILE')


# ----------------------------------------------------------------------------- parser


def cpp_parser() -> Any:
    """A tree-sitter parser for C++ (ImportError when the ``extract`` extra is not installed)."""
    import tree_sitter
    import tree_sitter_cpp

    return tree_sitter.Parser(tree_sitter.Language(tree_sitter_cpp.language()))


# ----------------------------------------------------------------------------- values


@dataclass(frozen=True, slots=True)
class _Unknown:
    """A value the source computes at run time; ``why`` completes 'is ...'."""

    why: str
    location: Location


@dataclass(frozen=True, slots=True)
class _ParamValue:
    """The value of a declared parameter (a name taken from it is a gap with a hint)."""

    name: str
    default: Any
    location: Location


@dataclass(slots=True)
class _Descriptor:
    fields: dict[str, Any] = field(default_factory=dict)


@dataclass(slots=True)
class _Helper:
    """An object of a helper class (image_transport::ImageTransport...)."""

    kind: str


@dataclass(slots=True)
class _NodeRef:
    node: ExtractedNode


_RUNTIME = 'computed at run time'


def _text(node: Any) -> str:
    return str(node.text.decode('utf-8', 'replace'))


def _squash(text: str) -> str:
    return re.sub(r'\s+', '', text)


_ESCAPES = {'n': '\n', 't': '\t', 'r': '\r', '0': '\0', '\\': '\\', '"': '"', "'": "'", 'a': '\a',
            'b': '\b', 'f': '\f', 'v': '\v', '?': '?'}


def _string(node: Any) -> str:
    """The value of a string_literal (escapes decoded) or raw_string_literal."""
    if node.type == 'raw_string_literal':
        content = [c for c in node.children if c.type == 'raw_string_content']
        return _text(content[0]) if content else ''
    out = []
    for child in node.children:
        if child.type == 'string_content':
            out.append(_text(child))
        elif child.type == 'escape_sequence':
            seq = _text(child)[1:]
            out.append(_ESCAPES.get(seq, seq))
    return ''.join(out)


def _number(text: str) -> int | float | None:
    text = text.replace("'", '')
    if text.startswith(('-', '+')):
        inner = _number(text[1:])
        return -inner if inner is not None and text[0] == '-' else inner
    body = re.sub(r'(?i)(ull|ll|ul|lu|u|l|f)$', '', text) if not text.lower().startswith('0x') \
        else re.sub(r'(?i)(ull|ll|ul|lu|u|l)$', '', text)
    try:
        if re.fullmatch(r'(?i)0x[0-9a-f]+|0b[01]+|0[0-7]*|[1-9][0-9]*', body):
            return int(body, 0) if not re.fullmatch(r'0[0-7]+', body) else int(body, 8)
        return float(body)
    except ValueError:
        return None


_DURATIONS = {'nanoseconds': 1, 'microseconds': 1_000, 'milliseconds': 1_000_000, 'seconds': 1_000_000_000,
              'minutes': 60_000_000_000, 'hours': 3_600_000_000_000}
_DURATION_SUFFIXES = {'ns': 1, 'us': 1_000, 'ms': 1_000_000, 's': 1_000_000_000, 'min': 60_000_000_000,
                      'h': 3_600_000_000_000}


# ----------------------------------------------------------------------------- the reader


@dataclass(slots=True)
class _Class:
    name: str           # qualified
    node: Any           # class_specifier
    file: str
    bases: list[str]
    members: dict[str, Any] = field(default_factory=dict)
    template_params: set[str] = field(default_factory=set)
    aliases: dict[str, str] = field(default_factory=dict)
    methods: list[tuple[Any, str]] = field(default_factory=list)   # (function_definition, file)


class _PackageReader:
    """Reads the parsed files of one package and fills an :class:`Extraction`."""

    def __init__(self, relative_to: str | None) -> None:
        self.relative_to = relative_to
        self.extraction = Extraction()
        self.trees: list[tuple[str, Any]] = []
        self.constants: dict[str, Any] = {}
        self.aliases: dict[str, str] = {}
        self.classes: dict[str, _Class] = {}
        self.functions: list[tuple[Any, str, str | None]] = []  # (definition, file, class name)
        self.instantiations: dict[str, list[tuple[str, Any]]] = {}  # class -> [(file, args node)]
        self.registered: dict[str, Location] = {}
        self.methods: dict[str, list[tuple[Any, str]]] = {}
        self.member_values: dict[tuple[str, str], Any] = {}
        self.walks: dict[tuple[int, str], list[Any]] = {}
        self.file = ''

    def walk(self, node: Any, kind: str) -> list[Any]:
        """:func:`_walk`, once per node and kind."""
        key = (node.id, kind)
        found = self.walks.get(key)
        if found is None:
            found = self.walks[key] = _walk(node, kind)
        return found

    # -- locations and diagnostics
    def loc(self, node: Any, file: str | None = None) -> Location:
        return Location(file or self.file, node.start_point[0] + 1, node.start_point[1] + 1)

    def shown(self, location: Location) -> str:
        from nodl.extract.writer import show_path

        return str(Location(show_path(location.file, self.relative_to), location.line, location.column))

    def report(self, code: str, message: str, location: Location,
               severity: Severity = Severity.WARNING) -> None:
        self.extraction.diagnostics.append(Diagnostic(severity, message, file=location.file,
                                                      line=location.line, column=location.column,
                                                      code=code))

    # -- pass 1: read files, collect declarations
    def add_file(self, path: str, parser: Any) -> None:
        """Read and parse one file; input problems are one diagnostic each."""
        self.extraction.files.append(path)
        try:
            size = os.path.getsize(path)
            if size > MAX_FILE_BYTES:
                self.report(_TOO_LARGE, f'{size} bytes is more than the {MAX_FILE_BYTES} a C++ source is '
                            'read to; not read (split it, or extract the node from the files that '
                            'create it)', Location(path, 1, 1))
                return
            with open(path, 'rb') as handle:
                data = handle.read()
        except OSError as error:
            from nodl.files import describe_os_error

            self.report(_UNREADABLE, f'cannot read this C++ source: {describe_os_error(error)}',
                        Location(path), Severity.ERROR)
            return
        if b'\0' in data[:8192]:
            self.report(_UNREADABLE, 'not a C++ source (binary data); not read', Location(path, 1, 1))
            return
        head = data[:4096]
        mark = _GENERATED_MARK.search(head) if b'enerated' in head or b'ENERATED' in head else None
        if mark is not None:
            line = data[:mark.start()].count(b'\n') + 1
            self.report(_GENERATED, 'generated code (it says so here); not read: extract the node from '
                        'the source it is generated from', Location(path, line, 1), Severity.INFO)
            return
        tree = parser.parse(_mask_macros(data))
        if tree.root_node.has_error:
            bad = _first_error(tree.root_node)
            where = Location(path, bad.start_point[0] + 1, bad.start_point[1] + 1) if bad is not None \
                else Location(path, 1, 1)
            self.report(_SYNTAX, 'the C++ parser cannot read the code from here (a macro it cannot '
                        'expand, or a syntax error); what this part creates may be missing from the '
                        'extraction', where)
        self.trees.append((path, tree))

    def collect(self) -> None:
        for path, tree in self.trees:
            self.file = path
            self._collect(tree.root_node, '', None)

    def _collect(self, node: Any, namespace: str, klass: _Class | None,
                 template_params: set[str] | None = None) -> None:
        for child in node.named_children:
            kind = child.type
            if kind == 'namespace_definition':
                name = child.child_by_field_name('name')
                inner = f'{namespace}{_text(name)}::' if name is not None else namespace
                body = child.child_by_field_name('body')
                if body is not None:
                    self._collect(body, inner, klass)
            elif kind in ('class_specifier', 'struct_specifier'):
                self._class(child, namespace, klass, template_params or set())
            elif kind == 'template_declaration':
                params = {_text(p.child_by_field_name('name') or p).split()[-1].lstrip('.')
                          for p in child.named_children
                          if p.type == 'template_parameter_list' for p in p.named_children}
                params = {p.split('=')[0].strip() for p in params}
                self._collect(child, namespace, klass, params)
            elif kind == 'function_definition':
                self._function(child, namespace, klass)
            elif kind in ('declaration', 'field_declaration'):
                self._declaration(child, namespace, klass)
                for spec in child.named_children:
                    if spec.type in ('class_specifier', 'struct_specifier') and \
                            spec.child_by_field_name('body') is not None:
                        self._class(spec, namespace, klass, set())
            elif kind in ('alias_declaration', 'type_definition'):
                self._alias(child, namespace, klass)
            elif kind == 'preproc_def':
                self._define(child)
            elif kind == 'preproc_function_def':
                value = child.child_by_field_name('value')
                if value is not None and any(call in _text(value) for call in _ENTITY_CALLS):
                    name = _text(child.child_by_field_name('name'))
                    self.report(_MACRO, f'the macro {name} creates entities; what it creates where it '
                                'is used is not extracted (write those entities in by hand)',
                                self.loc(child))
            elif kind in ('preproc_if', 'preproc_ifdef', 'preproc_else', 'preproc_elif',
                          'linkage_specification', 'declaration_list', 'field_declaration_list',
                          'access_specifier'):
                self._collect(child, namespace, klass, template_params)
            elif kind == 'expression_statement':
                self._toplevel_macro(child)
        if node.type == 'translation_unit':
            self._toplevel_macros(node)

    def _toplevel_macros(self, root: Any) -> None:
        for child in root.named_children:
            self._toplevel_macro(child)

    def _toplevel_macro(self, node: Any) -> None:
        text = _text(node)
        if 'RCLCPP_COMPONENTS_REGISTER_NODE' not in text:
            return
        match = re.search(r'RCLCPP_COMPONENTS_REGISTER_NODE\s*\(\s*([\w:]+)\s*\)', text)
        if match:
            self.registered.setdefault(match.group(1).lstrip(':'), self.loc(node))

    def _class(self, node: Any, namespace: str, outer: _Class | None, params: set[str]) -> None:
        name_node = node.child_by_field_name('name')
        body = node.child_by_field_name('body')
        if name_node is None or body is None:
            return
        prefix = f'{outer.name}::' if outer is not None else namespace
        qualified = f'{prefix}{_text(name_node)}'
        bases = []
        for clause in node.named_children:
            if clause.type == 'base_class_clause':
                for base in clause.named_children:
                    if base.type != 'access_specifier':
                        bases.append(_squash(_text(base)).lstrip(':'))
        klass = _Class(qualified, node, self.file, bases, template_params=set(params))
        self.classes.setdefault(qualified, klass)
        self._collect(body, namespace, klass)

    def _alias(self, node: Any, namespace: str, klass: _Class | None) -> None:
        if node.type == 'alias_declaration':
            name, value = node.child_by_field_name('name'), node.child_by_field_name('type')
        else:
            value = node.child_by_field_name('type')
            declarators = [c for c in node.children_by_field_name('declarator')]
            name = declarators[0] if declarators else None
        if name is None or value is None:
            return
        table = klass.aliases if klass is not None else self.aliases
        table[_text(name)] = _squash(_text(value))

    def _define(self, node: Any) -> None:
        name, value = node.child_by_field_name('name'), node.child_by_field_name('value')
        if name is None or value is None:
            return
        text = value.text.strip()
        parsed = _literal_text(text)
        if parsed is not None:
            self.constants[_text(name)] = parsed

    def _declaration(self, node: Any, namespace: str, klass: _Class | None) -> None:
        """Constants (const/constexpr) and members with their initial values."""
        qualifiers = {_text(c) for c in node.named_children if c.type in ('type_qualifier', 'storage_class_specifier')}
        for declarator in node.children_by_field_name('declarator'):
            target, value = _declarator_value(declarator, node)
            if target is None:
                continue
            if klass is not None and node.type == 'field_declaration':
                klass.members[target] = (value, qualifiers, self.loc(declarator))
                continue
            if value is not None and ({'const', 'constexpr'} & qualifiers):
                self.constants.setdefault(f'{namespace}{target}', (value, self.file))
                self.constants.setdefault(target, (value, self.file))

    def _function(self, node: Any, namespace: str, klass: _Class | None) -> None:
        declarator = node.child_by_field_name('declarator')
        while declarator is not None and declarator.type in ('pointer_declarator', 'reference_declarator'):
            declarator = declarator.child_by_field_name('declarator') or (
                declarator.named_children[-1] if declarator.named_children else None)
        name = declarator.child_by_field_name('declarator') if declarator is not None else None
        owner = klass.name if klass is not None else None
        if klass is None and name is not None and name.type == 'qualified_identifier':
            scope = _squash(_text(name)).rsplit('::', 1)[0]
            owner = f'{namespace}{scope}' if f'{namespace}{scope}' in self.classes or \
                not scope.startswith('::') else scope
            owner = owner.lstrip(':')
        self.functions.append((node, self.file, owner))

    # -- pass 2: node classes, then entities
    def node_base(self, name: str, seen: set[str] | None = None) -> str | None:
        klass = self.classes.get(name)
        if klass is None:
            return None
        seen = seen or set()
        for base in klass.bases:
            plain = re.sub(r'<.*>', '', base)
            if plain in _NODE_BASES:
                return _NODE_BASES[plain]
            other = self._class_named(plain, name)
            if other is not None and other not in seen:
                seen.add(other)
                found = self.node_base(other, seen)
                if found is not None:
                    return found
        return None

    def _class_named(self, name: str, near: str) -> str | None:
        if name in self.classes:
            return name
        scope = near.rsplit('::', 1)[0] if '::' in near else ''
        while True:
            candidate = f'{scope}::{name}' if scope else name
            if candidate in self.classes:
                return candidate
            if not scope:
                break
            scope = scope.rsplit('::', 1)[0] if '::' in scope else ''
        ends = [c for c in self.classes if c.endswith(f'::{name}')]
        return ends[0] if len(ends) == 1 else None

    def owner_class(self, owner: str | None) -> str | None:
        if owner is None:
            return None
        if owner in self.classes:
            return owner
        return self._class_named(owner, owner)

    def run(self, targets: CMakeTargets | None, package: str | None) -> Extraction:
        self.collect()
        nodes: dict[str, ExtractedNode] = {}
        for name, klass in self.classes.items():
            base = self.node_base(name)
            if base is None:
                continue
            node = ExtractedNode(name=name, location=Location(klass.file, klass.node.start_point[0] + 1,
                                                               klass.node.start_point[1] + 1),
                                 language='cpp', base=base, package=package)
            node.sources.append(klass.file)
            nodes[name] = node
        self._instantiations()
        for name, node in nodes.items():
            _NodeScan(self, self.classes[name], node).scan()
        free: list[ExtractedNode] = []
        for definition, file, owner in self.functions:
            if self.owner_class(owner) in nodes:
                continue
            self.file = file
            _FreeScan(self, definition, free, package).scan()
        # inherited entities: a node class gets its node bases' entities
        for name, node in nodes.items():
            for base in self._base_chain(name):
                if base in nodes:
                    node.entities = [*nodes[base].entities, *node.entities]
                    node.sources += [s for s in nodes[base].sources if s not in node.sources]
        ordered = list(nodes.values()) + free
        for node in ordered:
            node.entities.sort(key=lambda e: (e.location.file, e.location.line, e.location.column))
            self._map_executable(node, targets)
        self.extraction.nodes += ordered
        return self.extraction

    def _base_chain(self, name: str) -> list[str]:
        out: list[str] = []
        klass = self.classes.get(name)
        while klass is not None:
            nxt = None
            for base in klass.bases:
                other = self._class_named(re.sub(r'<.*>', '', base), klass.name)
                if other is not None and other not in out and other != name:
                    nxt = other
                    break
            if nxt is None:
                break
            out.append(nxt)
            klass = self.classes.get(nxt)
        return out

    def _instantiations(self) -> None:
        """``std::make_shared<C>(...)``, ``std::make_unique<C>(...)``, ``C node(...)``: where each
        node class is created (its executable's main, its constructor's arguments)."""
        for path, tree in self.trees:
            if b'make_shared<' not in tree.root_node.text and b'make_unique<' not in tree.root_node.text:
                continue
            for call in _walk(tree.root_node, _TEMPLATE_CALLS):
                function = call.child_by_field_name('function')
                if function is None:
                    continue
                text = _squash(_text(function))
                match = re.fullmatch(r'(?:std::)?make_(?:shared|unique)<(.+)>', text)
                if match:
                    self.instantiations.setdefault(match.group(1).lstrip(':'), []).append(
                        (path, call.child_by_field_name('arguments')))

    def _map_executable(self, node: ExtractedNode, targets: CMakeTargets | None) -> None:
        registered = self.registered.get(node.name)
        if node.made_by == 'class' and (registered is not None or (
                targets is not None and targets.library_of_plugin(node.name) is not None)):
            node.plugin = node.name  # a component: the class is what a container loads
        if targets is None:
            if registered is not None and node.executable is None:
                node.notes.append(Diagnostic(Severity.INFO, f'{node.name} is a component '
                                             '(RCLCPP_COMPONENTS_REGISTER_NODE); no CMakeLists.txt was '
                                             'read to name its executable', file=registered.file,
                                             line=registered.line, column=registered.column,
                                             code=_UNTIED))
            return
        if node.executable is not None:
            return
        executable = targets.executable_of_plugin(node.name)
        if executable is None:
            files = {node.location.file} | {f for f, _ in self.instantiations.get(node.name, [])}
            short = node.name.rsplit('::', 1)[-1]
            files |= {f for c, places in self.instantiations.items()
                      if c.rsplit('::', 1)[-1] == short for f, _ in places}
            executable = targets.executable_of_sources(files)
        if executable is not None:
            node.executable = executable
            if targets.package is not None:
                node.package = targets.package
            return
        library = targets.library_of_plugin(node.name)
        where = registered or node.location
        what = (f'a component (plugin {node.name} of library {library}) with no executable of its own'
                if library is not None else 'not built into an executable CMakeLists.txt names')
        node.notes.append(Diagnostic(Severity.INFO, f'{node.name} is {what}; its draft is named after '
                                     'the class', file=where.file, line=where.line, column=where.column,
                                     code=_UNTIED))


_PRI = re.compile(rb'\bPRI[diouxX](?:8|16|32|64|MAX|PTR|FAST[0-9]+|LEAST[0-9]+)\b')
_EXPORT = re.compile(rb'\b[A-Z][A-Z0-9]*(?:_[A-Z0-9]+)*_(?:PUBLIC|EXPORT|LOCAL|API|DLL|IMPORT|PUBLIC_TYPE|'
                     rb'VISIBILITY_[A-Z]+)\b(?!\s*\()')
_CLASS_MACRO = re.compile(rb'(?<=\bclass )(\s*[A-Z][A-Z0-9_]+)(?=\s+[A-Za-z_])')
_REGISTER = re.compile(rb'(RCLCPP_COMPONENTS_REGISTER_NODE\s*\([^()]*\))(?!\s*;)')


def _mask_macros(data: bytes) -> bytes:
    """The source with the macros the grammar cannot read made harmless, every line and column
    kept: export/visibility macros (``DEMO_NODES_CPP_PUBLIC``, ``class FOO_EXPORT Name``) become
    spaces, ``PRId64`` in a string concatenation a string literal of the same width, and
    ``RCLCPP_COMPONENTS_REGISTER_NODE(...)`` gains the ``;`` it leaves out (at the end)."""
    if b'PRI' in data:
        data = _PRI.sub(lambda m: b'"d"'.ljust(len(m.group()), b' '), data)
    if any(word in data for word in (b'_PUBLIC', b'_EXPORT', b'_LOCAL', b'_API', b'_DLL', b'_IMPORT',
                                     b'_VISIBILITY_')):
        data = _EXPORT.sub(lambda m: b' ' * len(m.group()), data)
    if b'class ' in data:
        data = _CLASS_MACRO.sub(lambda m: b' ' * len(m.group()), data)
    if b'RCLCPP_COMPONENTS_REGISTER_NODE' in data:
        data = _REGISTER.sub(lambda m: m.group(1) + b';', data)
    return data


def _first_error(node: Any) -> Any:
    if node.type == 'ERROR' or node.is_missing:
        return node
    for child in node.children:
        if child.has_error or child.is_missing:
            found = _first_error(child)
            if found is not None:
                return found
    return None


_QUERIES: dict[str, Any] = {}
#: A query (not a node type) for :func:`_walk`: the calls of a function template (``f<T>(...)``,
#: ``ns::f<T>(...)``), where ``std::make_shared<Node>(...)`` is found.
_TEMPLATE_CALLS = ('(call_expression function: [(template_function) '
                   '(qualified_identifier name: (template_function))]) @found')


def _walk(node: Any, kind: str) -> list[Any]:
    """The nodes of type ``kind`` in ``node`` (itself included), in source order (an enclosing
    node before the nodes it holds): found by a tree-sitter query, in C, not node by node."""
    import tree_sitter

    query = _QUERIES.get(kind)
    if query is None:
        import tree_sitter_cpp

        query = _QUERIES[kind] = tree_sitter.Query(tree_sitter.Language(tree_sitter_cpp.language()),
                                                   kind if kind.startswith('(') else f'({kind}) @found')
    found = list(tree_sitter.QueryCursor(query).captures(node).get('found', []))
    found.sort(key=lambda n: (n.start_byte, -n.end_byte))
    return found


#: Nodes that hold no call, declaration or assignment: not visited.
_INERT = frozenset({'identifier', 'field_identifier', 'string_literal', 'raw_string_literal', 'number_literal',
                    'comment', 'this', 'namespace_identifier', 'type_identifier', 'qualified_identifier',
                    'template_argument_list', 'type_descriptor', 'primitive_type', 'true', 'false', 'null',
                    'nullptr', 'string_content', 'escape_sequence', 'char_literal', 'concatenated_string',
                    'break_statement', 'continue_statement', 'goto_statement', 'sized_type_specifier'})
#: Statements skipped when they hold neither a candidate call nor an assignment (their own
#: declarations are local to them).
_PRUNABLE = frozenset({'expression_statement', 'return_statement', 'if_statement', 'for_statement',
                       'while_statement', 'for_range_loop', 'do_statement', 'switch_statement', 'try_statement',
                       'compound_statement', 'lambda_expression'})
#: What a function body must hold for scanning it to find anything: an entity call, a helper
#: that creates entities, a message_filters or image_transport object (a byte search first).
_CANDIDATE = re.compile(rb'create_|declare_parameter|TransformBroadcaster|TransformListener|Updater|'
                        rb'message_filters|image_transport|ImageTransport|advertise|subscribe')


def _literal_text(text: bytes) -> Any:
    """The value of a #define's replacement text when it is one literal, else None."""
    raw = text.decode('utf-8', 'replace').strip()
    match = re.fullmatch(r'"((?:[^"\\]|\\.)*)"', raw)
    if match:
        return (match.group(1), '')
    number = _number(raw) if re.fullmatch(r'-?[0-9][0-9a-zA-Z.\']*', raw) else None
    if number is not None:
        return (number, '')
    return None


def _declarator_value(declarator: Any, declaration: Any) -> tuple[str | None, Any]:
    """(name, value node) of one declarator: ``x = v``, ``x{v}``, ``x(v)``, or ``x`` (None)."""
    if declarator.type == 'init_declarator':
        inner = declarator.child_by_field_name('declarator')
        value = declarator.child_by_field_name('value')
        name = _declared_name(inner)
        return name, value
    name = _declared_name(declarator)
    value = declaration.child_by_field_name('default_value')
    return name, value


def _declared_name(node: Any) -> str | None:
    while node is not None and node.type not in ('identifier', 'field_identifier', 'qualified_identifier'):
        inner = node.child_by_field_name('declarator')
        if inner is None:
            named = [c for c in node.named_children if c.type in ('identifier', 'field_identifier')]
            return _text(named[0]) if named else None
        node = inner
    return _text(node) if node is not None else None


# ----------------------------------------------------------------------------- scanning bodies

_INT_TYPES = {'int', 'int64_t', 'int32_t', 'int16_t', 'int8_t', 'long', 'longlong', 'short', 'uint8_t',
              'uint16_t', 'uint32_t', 'uint64_t', 'size_t', 'unsigned', 'unsignedint', 'std::int64_t',
              'std::int32_t', 'std::size_t'}
#: ``rclcpp::ParameterType`` constant -> parameter type (the vocabulary's table; ``PARAMETER_NOT_SET``
#: declares no type).
_PARAM_ENUM = {name: word for word, name in ROS_PARAMETER_TYPE_NAMES.items() if word != 'none'}


def _param_type(cpp: str) -> str | None:
    cpp = cpp.replace('const', '').replace('&', '')
    if cpp == 'bool':
        return 'bool'
    if cpp in _INT_TYPES:
        return 'int'
    if cpp in ('double', 'float'):
        return 'double'
    if cpp in ('std::string', 'string'):
        return 'string'
    match = re.fullmatch(r'(?:std::)?vector<(.+)>', cpp)
    if match:
        inner = match.group(1)
        if inner in ('uint8_t', 'std::uint8_t', 'unsignedchar'):
            return 'byte_array'
        scalar = _param_type(inner)
        return f'{scalar}_array' if scalar in ('bool', 'int', 'double', 'string') else None
    return None


def _value_type(value: Any) -> str | None:
    if isinstance(value, bool):
        return 'bool'
    if isinstance(value, int):
        return 'int'
    if isinstance(value, float):
        return 'double'
    if isinstance(value, str):
        return 'string'
    if isinstance(value, list) and value:
        kinds = {_value_type(v) for v in value}
        if kinds == {'int', 'double'}:
            return 'double_array'
        if len(kinds) == 1 and None not in kinds:
            return f'{kinds.pop()}_array'
    return None


def _fit(value: Any, kind: str | None) -> Any:
    if kind == 'double' and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if kind == 'double_array' and isinstance(value, list):
        return [float(v) if isinstance(v, int) and not isinstance(v, bool) else v for v in value]
    return value


class _BodyScan:
    """Reads function bodies in source order, keeping the values of local variables."""

    def __init__(self, reader: _PackageReader, klass: _Class | None) -> None:
        self.r = reader
        self.klass = klass
        self.scope: dict[str, Any] = {}
        self.depth = 0

    # entity sink: overridden
    def node_for(self, receiver: Any) -> ExtractedNode | None:
        raise NotImplementedError

    def visit(self, node: Any) -> None:
        kind = node.type
        if kind in _PRUNABLE:  # no candidate call and no assignment: nothing here to read
            text = node.text
            if b'=' not in text and _CANDIDATE.search(text) is None:
                return
        if kind == 'declaration':
            self._local(node)
            return
        if kind == 'assignment_expression':
            self.visit(node.child_by_field_name('right'))
            self._assign(node)
            return
        if kind == 'call_expression' and self._call(node):
            return
        nested = kind in ('if_statement', 'for_statement', 'while_statement', 'for_range_loop',
                          'do_statement', 'switch_statement', 'lambda_expression', 'try_statement')
        self.depth += nested
        for child in node.named_children:
            if child.type not in _INERT:
                self.visit(child)
        self.depth -= nested

    def _local(self, node: Any) -> None:
        type_node = node.child_by_field_name('type')
        type_text = _squash(_text(type_node)) if type_node is not None else ''
        for declarator in node.children_by_field_name('declarator'):
            name, value = _declarator_value(declarator, node)
            if value is not None:
                self.visit(value)
            if name is None:
                continue
            if declarator.type == 'init_declarator' and value is not None and value.type == 'argument_list':
                self.scope[name] = self.construct(type_text, value, declarator)
            elif value is not None:
                if value.type == 'initializer_list' and type_text not in ('auto', ''):
                    self.scope[name] = self.construct(type_text, value, declarator)
                else:
                    self.scope[name] = self.value(value)
            else:
                self.scope[name] = self.construct(type_text, None, declarator)

    def construct(self, type_text: str, args: Any, where: Any) -> Any:
        """The value of ``Type name(args)`` / ``Type name{args}`` / ``Type name;``."""
        plain = re.sub(r'<.*>', '', type_text)
        if plain.endswith('ParameterDescriptor'):
            return _Descriptor()
        if plain.endswith(('FloatingPointRange', 'IntegerRange')):
            return _Descriptor()
        if plain.endswith('QoS') or plain in ('rclcpp::KeepLast', 'KeepLast'):
            return self.qos_call(type_text, args, where)
        if plain.endswith('ImageTransport'):
            return _Helper('image_transport')
        if args is None:
            return _Unknown(_RUNTIME, self.r.loc(where))
        helper = self.helper(type_text, args, where)
        if helper:
            return _Unknown('a helper', self.r.loc(where))
        items = [a for a in args.named_children if a.type != 'comment']
        if plain in ('std::string', 'string', 'std::vector', 'vector') and len(items) == 1:
            return self.value(items[0])
        if plain in ('std::map', 'map'):
            return self.value(args)
        return _Unknown(_RUNTIME, self.r.loc(where))

    def _assign(self, node: Any) -> None:
        left, right = node.child_by_field_name('left'), node.child_by_field_name('right')
        if left is None or right is None:
            return
        if left.type == 'field_expression':
            obj = left.child_by_field_name('argument')
            fld = left.child_by_field_name('field')
            target = self.scope.get(_text(obj)) if obj is not None else None
            if isinstance(target, _Descriptor) and fld is not None:
                target.fields[_text(fld)] = self.value(right) if self.depth == 0 else \
                    _Unknown('set conditionally', self.r.loc(node))
            return
        if left.type == 'identifier' and _text(left) in self.scope:
            self.scope[_text(left)] = self.value(right) if self.depth == 0 else \
                _Unknown('set conditionally', self.r.loc(node))

    # -- values
    def lookup(self, name: str, where: Any) -> Any:
        if name in self.scope:
            return self.scope[name]
        bare = name[len('this->'):] if name.startswith('this->') else name
        if self.klass is not None:
            for klass in self._klasses():
                if bare in klass.members:
                    return self.r_member(klass, bare, where)
        key = name.lstrip(':')
        constant = self.r.constants.get(key)
        if constant is None and '::' in key:
            constant = self.r.constants.get(key.rsplit('::', 1)[-1])
        if constant is not None:
            value, file = constant
            if not file:  # a #define of a literal
                return value
            saved = self.r.file
            self.r.file = file
            try:
                return _BodyScan(self.r, None).value(value)
            finally:
                self.r.file = saved
        return _Unknown(_RUNTIME, self.r.loc(where))

    def _klasses(self) -> list[_Class]:
        assert self.klass is not None
        out = [self.klass]
        for base in self.r._base_chain(self.klass.name):
            if base in self.r.classes:
                out.append(self.r.classes[base])
        return out

    def r_member(self, klass: _Class, name: str, where: Any) -> Any:
        key = (klass.name, name)
        if key not in self.r.member_values:
            self.r.member_values[key] = _member_value(self.r, klass, name, where)
        value = self.r.member_values[key]
        return _Unknown(value.why, self.r.loc(where)) if isinstance(value, _Unknown) else value

    def value(self, node: Any) -> Any:
        """A compile-time value, or :class:`_Unknown`."""
        if node is None:
            return _Unknown(_RUNTIME, Location(self.r.file))
        kind = node.type
        if kind in ('string_literal', 'raw_string_literal'):
            return _string(node)
        if kind == 'concatenated_string':
            parts = [self.value(c) for c in node.named_children]
            return ''.join(parts) if all(isinstance(p, str) for p in parts) else \
                next(p for p in parts if not isinstance(p, str))
        if kind == 'number_literal':
            number = _number(_text(node))
            return number if number is not None else _Unknown(_RUNTIME, self.r.loc(node))
        if kind == 'true':
            return True
        if kind == 'false':
            return False
        if kind == 'parenthesized_expression' and node.named_children:
            return self.value(node.named_children[0])
        if kind == 'unary_expression':
            operand = self.value(node.child_by_field_name('argument'))
            op = _text(node.child_by_field_name('operator'))
            if isinstance(operand, (int, float)) and not isinstance(operand, bool) and op in ('-', '+'):
                return -operand if op == '-' else operand
            if isinstance(operand, bool) and op == '!':
                return not operand
            return operand if isinstance(operand, (_Unknown, _ParamValue)) else _Unknown(_RUNTIME, self.r.loc(node))
        if kind == 'binary_expression':
            left = self.value(node.child_by_field_name('left'))
            right = self.value(node.child_by_field_name('right'))
            op = _text(node.child_by_field_name('operator'))
            if op == '+' and isinstance(left, str) and isinstance(right, str):
                return left + right
            for side in (left, right):
                if isinstance(side, (_Unknown, _ParamValue)):
                    return side
            return _Unknown(_RUNTIME, self.r.loc(node))
        if kind in ('identifier', 'qualified_identifier', 'field_identifier'):
            return self.lookup(_squash(_text(node)), node)
        if kind == 'field_expression':
            obj = node.child_by_field_name('argument')
            fld = node.child_by_field_name('field')
            if obj is not None and obj.type == 'this' and fld is not None:
                return self.lookup(_text(fld), node)
            return _Unknown(_RUNTIME, self.r.loc(node))
        if kind == 'initializer_list':
            items = [self.value(c) for c in node.named_children if c.type != 'comment']
            bad = [i for i in items if isinstance(i, (_Unknown, _ParamValue))]
            if bad:
                return bad[0]
            if items and all(isinstance(i, list) and len(i) == 2 and isinstance(i[0], str) for i in items):
                return {i[0]: i[1] for i in items}
            return items
        if kind == 'compound_literal_expression':
            body = node.child_by_field_name('value')
            type_text = _squash(_text(node.child_by_field_name('type')))
            value = self.value(body)
            if isinstance(value, list) and len(value) == 1 and re.sub(r'<.*>', '', type_text) in (
                    'std::string', 'rclcpp::ParameterValue'):
                return value[0]
            if isinstance(value, list) and _param_type(type_text) is not None and \
                    not _param_type(type_text).endswith('_array'):  # type: ignore[union-attr]
                return value[0] if len(value) == 1 else _Unknown(_RUNTIME, self.r.loc(node))
            return value
        if kind == 'call_expression':
            return self.call_value(node)
        if kind == 'user_defined_literal':
            return _Unknown(_RUNTIME, self.r.loc(node))
        return _Unknown(_RUNTIME, self.r.loc(node))

    def call_value(self, node: Any) -> Any:
        function = node.child_by_field_name('function')
        args = node.child_by_field_name('arguments')
        items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
        name = _squash(_text(function)) if function is not None else ''
        plain = re.sub(r'<.*>', '', name)
        if plain in ('std::string', 'string', 'rclcpp::ParameterValue', 'ParameterValue',
                     'std::vector', 'static_cast', 'std::string_view') and len(items) == 1:
            return self.value(items[0])
        if function is not None and function.type == 'field_expression':
            field_name = function.child_by_field_name('field')
            obj = function.child_by_field_name('argument')
            method = _text(field_name) if field_name is not None else ''
            if method in ('c_str', 'data', 'str') and obj is not None:
                return self.value(obj)
            if method.startswith('set__') and obj is not None:
                base = self.value(obj)
                if isinstance(base, _Descriptor) and items:
                    base.fields[method[len('set__'):]] = self.value(items[0])
                    return base
            if method in ('as_string', 'as_int', 'as_double', 'as_bool', 'get_value', 'as_string_array',
                          'as_double_array', 'as_integer_array', 'as_bool_array') and obj is not None:
                inner = self.value(obj)
                if isinstance(inner, _ParamValue):
                    return inner
        if (plain.endswith('get_parameter') or plain.endswith('get_parameter_or')) and items:
            pname = self.value(items[0])
            if isinstance(pname, str):
                return _ParamValue(pname, None, self.r.loc(node))
        if plain.endswith('declare_parameter'):
            found = self._declare_parameter(node, function, items, record=False)
            if found is not None:
                return found
        if plain.endswith(('QoS', 'KeepLast', 'KeepAll')) or (
                function is not None and function.type == 'field_expression' and self._is_qos_chain(function)):
            return self.qos_value(node)
        return _Unknown(_RUNTIME, self.r.loc(node))

    def _is_qos_chain(self, function: Any) -> bool:
        method = function.child_by_field_name('field')
        return method is not None and _text(method) in _QOS_METHODS

    # -- QoS
    def qos_value(self, node: Any) -> Any:
        """The QoSProfile an expression stands for, or :class:`_Unknown`."""
        from dataclasses import replace

        from nodl.model.qos import QoSProfile

        kind = node.type
        if kind in ('number_literal', 'identifier', 'qualified_identifier', 'field_expression',
                    'parenthesized_expression'):
            named = qos_of_name(_squash(_text(node))) if kind != 'number_literal' else None
            if named is not None:
                return named
            value = self.value(node) if kind != 'field_expression' or _text(node).startswith('this') else \
                _Unknown(_RUNTIME, self.r.loc(node))
            if isinstance(value, QoSProfile):
                return replace(value)
            if isinstance(value, int) and not isinstance(value, bool) and value > 0:
                return _depth_qos(value)
            if isinstance(value, _ParamValue):
                return value
            return _Unknown(_RUNTIME, self.r.loc(node))
        if kind == 'call_expression':
            function = node.child_by_field_name('function')
            args = node.child_by_field_name('arguments')
            if function is None:
                return _Unknown(_RUNTIME, self.r.loc(node))
            if function.type == 'field_expression':
                obj = function.child_by_field_name('argument')
                method = function.child_by_field_name('field')
                base = self.qos_value(obj)
                if isinstance(base, (QoSProfile,)):
                    return self.apply(replace(base), _text(method), args, node)
                return base
            return self.qos_call(_squash(_text(function)), args, node)
        if kind == 'compound_literal_expression':
            return self.qos_call(_squash(_text(node.child_by_field_name('type'))),
                                 node.child_by_field_name('value'), node)
        return _Unknown(_RUNTIME, self.r.loc(node))

    def qos_call(self, name: str, args: Any, where: Any) -> Any:
        from dataclasses import replace

        from nodl.model.qos import QoSProfile

        items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
        named = qos_of_name(name)
        if named is not None:
            if items and name.rsplit('::', 1)[-1].endswith('QoS'):
                history = self.qos_value(items[0])
                if not isinstance(history, QoSProfile):
                    return history
                named.history, named.depth = history.history, history.depth
            return named
        short = name.rsplit('::', 1)[-1]
        if short in ('KeepLast',):
            depth = self.value(items[0]) if items else None
            if isinstance(depth, int) and not isinstance(depth, bool) and depth > 0:
                return _depth_qos(depth)
            return depth if isinstance(depth, (_Unknown, _ParamValue)) else _Unknown(_RUNTIME, self.r.loc(where))
        if short == 'KeepAll':
            return QoSProfile(history='KEEP_ALL', reliability='RELIABLE', durability='VOLATILE')
        if short == 'QoS':
            if not items:
                return _Unknown(_RUNTIME, self.r.loc(where))
            first = items[0]
            if _squash(_text(first)).startswith(('rclcpp::QoSInitialization::from_rmw', 'QoSInitialization::from_rmw')):
                inner = first.child_by_field_name('arguments')
                profile = self.qos_value(inner.named_children[0]) if inner is not None and inner.named_children \
                    else _Unknown(_RUNTIME, self.r.loc(first))
            else:
                profile = self.qos_value(first)
            if not isinstance(profile, QoSProfile):
                if isinstance(profile, (_Unknown, _ParamValue)):
                    return profile
                return _Unknown(_RUNTIME, self.r.loc(first))
            if len(items) > 1:
                policies = self.qos_value(items[1])
                if not isinstance(policies, QoSProfile):
                    return policies
                return replace(policies, history=profile.history, depth=profile.depth)
            return profile
        return _Unknown(_RUNTIME, self.r.loc(where))

    def apply(self, qos: QoSProfile, method: str, args: Any, where: Any) -> Any:
        items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
        if method in _POLICY_WORDS and method not in ('keep_last', 'automatic', 'manual_by_topic'):
            word = _POLICY_WORDS[method]
            if method in ('reliable', 'best_effort'):
                qos.reliability = word
            elif method in ('transient_local',):
                qos.durability = word
            elif method == 'keep_all':
                qos.history, qos.depth = 'KEEP_ALL', None
            return qos
        if method == 'durability_volatile':
            qos.durability = 'VOLATILE'
            return qos
        if method in ('reliability_best_available', 'durability_best_available'):
            setattr(qos, method.split('_')[0], 'BEST_AVAILABLE')
            return qos
        if method == 'keep_last':
            depth = self.value(items[0]) if items else None
            if isinstance(depth, int) and not isinstance(depth, bool) and depth > 0:
                qos.history, qos.depth = 'KEEP_LAST', depth
                return qos
            return _Unknown(_RUNTIME, self.r.loc(items[0] if items else where))
        if method in ('reliability', 'durability', 'history', 'liveliness') and items:
            policy = _policy(_squash(_text(items[0])))
            if policy is None:
                return _Unknown(_RUNTIME, self.r.loc(items[0]))
            if method == 'history':
                if policy == 'KEEP_ALL':
                    qos.depth = None
                qos.history = policy
            else:
                setattr(qos, method, policy)
            return qos
        if method in ('deadline', 'lifespan', 'liveliness_lease_duration') and items:
            ns = self.duration(items[0])
            if ns is None:
                return _Unknown(_RUNTIME, self.r.loc(items[0]))
            setattr(qos, f'{method}_ns', ns)
            return qos
        if method in ('avoid_ros_namespace_conventions',):
            return qos
        return _Unknown(_RUNTIME, self.r.loc(where))

    def duration(self, node: Any) -> int | None:
        text = _squash(_text(node))
        match = re.fullmatch(r'([0-9.]+)(ns|us|ms|s|min|h)', text)
        if match:
            return int(float(match.group(1)) * _DURATION_SUFFIXES[match.group(2)])
        match = re.fullmatch(r'(?:std::)?chrono::(\w+)\(([0-9.]+)\)', text)
        if match and match.group(1) in _DURATIONS:
            return int(float(match.group(2)) * _DURATIONS[match.group(1)])
        match = re.fullmatch(r'rclcpp::Duration(?:::from_seconds)?\(([0-9.]+)(?:,([0-9]+))?\)', text)
        if match:
            seconds = float(match.group(1))
            return int(seconds * 1_000_000_000) + int(match.group(2) or 0)
        return None

    # -- calls
    def _call(self, node: Any) -> bool:
        """Handle an entity-creating call; True when its arguments need no further visit."""
        function = node.child_by_field_name('function')
        args = node.child_by_field_name('arguments')
        if function is None or args is None:
            return False
        items = [a for a in args.named_children if a.type != 'comment']
        receiver, method, template = _split_call(function)
        if method is None:
            return False
        if method == 'create_server' and receiver in ('rclcpp_action',):
            self._action(node, items, template, 'action_servers')
        elif method == 'create_client' and receiver in ('rclcpp_action',):
            self._action(node, items, template, 'action_clients')
        elif method in ('create_publisher', 'create_subscription', 'create_service', 'create_client',
                        'create_generic_publisher', 'create_generic_subscription') and \
                receiver not in ('image_transport', 'rclcpp_action'):
            owner = self.node_for(receiver)
            if owner is None:
                if receiver not in (None, 'this'):
                    self.untied(node, method, receiver)
                return False
            self._endpoint(owner, node, method, items, template)
        elif method in ('declare_parameter', 'declare_parameters'):
            owner = self.node_for(receiver)
            if owner is None:
                if receiver not in (None, 'this'):
                    self.untied(node, method, receiver)
                return False
            if method == 'declare_parameter':
                self._declare_parameter(node, function, items, record=True)
            else:
                self._declare_parameters(owner, node, items, template)
        elif receiver == 'image_transport' and method in ('create_publisher', 'create_subscription',
                                                          'create_camera_publisher', 'create_camera_subscription'):
            self._image_transport(node, items[1] if len(items) > 1 else None, method)
        elif method in ('advertise', 'subscribe', 'advertiseCamera', 'subscribeCamera') and receiver is not None \
                and isinstance(self.scope.get(receiver), _Helper):
            self._image_transport(node, items[0] if items else None, method)
        elif method == 'subscribe' and receiver is not None and receiver in self.filters:
            self._filter_subscribe(node, items, receiver)
        else:
            self.helper(_squash(_text(function)), args, node)
        return False

    filters: dict[str, str] = {}

    def untied(self, node: Any, method: str, receiver: str) -> None:
        self.r.report(_UNTIED, f'{method} on {receiver!r} here is not tied to a node the extraction knows '
                      '(a node passed in, or held by a helper class): not extracted',
                      self.r.loc(node), Severity.INFO)

    def type_of(self, template: Any, node: Any) -> tuple[str | None, Gap | None]:
        if template is None:
            return None, Gap('type', f'the interface type at {self.r.shown(self.r.loc(node))} is not given '
                             'as a template argument', self.r.loc(node), _TYPE)
        args = [a for a in template.named_children if a.type != 'comment']
        if not args:
            return None, Gap('type', 'no interface type', self.r.loc(template), _TYPE)
        text = _squash(_text(args[0]))
        return self.interface_type(text, args[0])

    def interface_type(self, text: str, where: Any) -> tuple[str | None, Gap | None]:
        for _ in range(8):
            resolved = None
            for klass in (self._klasses() if self.klass is not None else []):
                if text in klass.aliases:
                    resolved = klass.aliases[text]
            resolved = resolved or self.r.aliases.get(text) or self.r.aliases.get(text.rsplit('::', 1)[-1]) \
                if '::' not in text else resolved or self.r.aliases.get(text)
            if resolved is None or resolved == text:
                break
            text = resolved
        text = text.lstrip(':')
        if self.klass is not None and text in self.klass.template_params:
            return None, Gap('type', f'the interface type at {self.r.shown(self.r.loc(where))} is the template '
                             f'parameter {text}: it depends on how the template is used',
                             self.r.loc(where), _TEMPLATE)
        match = re.fullmatch(r'([a-z][a-z0-9_]*)::(msg|srv|action)::([A-Z][A-Za-z0-9]*)', text)
        if match:
            return '/'.join(match.groups()), None
        return None, Gap('type', f'the interface type {text} at {self.r.shown(self.r.loc(where))} is not a ROS '
                         'interface type the extraction can resolve (a type adapter, or an alias it does not '
                         'see)', self.r.loc(where), _TYPE)

    def name_of(self, arg: Any, what: str, where: Any) -> tuple[str | None, Gap | None]:
        if arg is None:
            return None, Gap('name', f'{what} at {self.r.shown(self.r.loc(where))} is not given',
                             self.r.loc(where), _NAME)
        value = self.value(arg)
        if isinstance(value, str):
            return value, None
        location = self.r.loc(arg)
        if isinstance(value, _ParamValue):
            default = f', default {value.default!r}' if isinstance(value.default, str) else ''
            return None, Gap('name', f'{what} at {self.r.shown(location)} is the value of parameter '
                             f'{value.name!r} (declared at {self.r.shown(value.location)}{default}): it is set '
                             'when the node starts; fill in the name it gets, or remap', location, _PARAM_NAME)
        return None, Gap('name', f'{what} at {self.r.shown(location)} is {_RUNTIME}', location, _NAME)

    def qos_of(self, arg: Any) -> tuple[Any, Gap | None]:
        from nodl.model.qos import QoSProfile

        value = self.qos_value(arg)
        if isinstance(value, QoSProfile):
            return value, None
        location = self.r.loc(arg)
        if isinstance(value, _ParamValue):
            return None, Gap('qos', f'QoS at {self.r.shown(location)} comes from parameter {value.name!r}: '
                             'it is set when the node starts', location, _QOS)
        return None, Gap('qos', f'QoS at {self.r.shown(location)} is {_RUNTIME}', location, _QOS)

    def _endpoint(self, owner: ExtractedNode, node: Any, method: str, items: list[Any], template: Any) -> None:
        section = {'create_publisher': 'publishers', 'create_subscription': 'subscriptions',
                   'create_service': 'service_servers', 'create_client': 'service_clients',
                   'create_generic_publisher': 'publishers',
                   'create_generic_subscription': 'subscriptions'}[method]
        word = 'topic' if section in ('publishers', 'subscriptions') else 'service'
        gaps: list[Gap] = []
        name, gap = self.name_of(items[0] if items else None, f'{word} name', node)
        gaps += [gap] if gap else []
        if method.startswith('create_generic'):
            kind, gap = None, None
            if len(items) < 2:
                gap = Gap('type', 'no type given', self.r.loc(node), _TYPE)
            else:
                value = self.value(items[1])
                if isinstance(value, str) and re.fullmatch(r'[a-z][a-z0-9_]*/msg/[A-Z][A-Za-z0-9]*', value):
                    kind = value
                else:
                    gap = Gap('type', f'the message type at {self.r.shown(self.r.loc(items[1]))} of a generic '
                              f'{"publisher" if section == "publishers" else "subscription"} is {_RUNTIME}',
                              self.r.loc(items[1]), _TYPE)
            qos_arg = items[2] if len(items) > 2 else None
        else:
            kind, gap = self.type_of(template, node)
            qos_arg = items[1] if len(items) > 1 and word == 'topic' else None
        gaps += [gap] if gap else []
        qos = None
        if word == 'topic':
            if qos_arg is None:
                gaps.append(Gap('qos', 'no QoS given', self.r.loc(node), _QOS))
            else:
                qos, gap = self.qos_of(qos_arg)
                gaps += [gap] if gap else []
        owner.entities.append(ExtractedEntity(section, name, kind, self.r.loc(node), qos=qos, gaps=gaps))
        self._source(owner)

    def _source(self, owner: ExtractedNode) -> None:
        if self.r.file not in owner.sources:
            owner.sources.append(self.r.file)

    def _action(self, node: Any, items: list[Any], template: Any, section: str) -> None:
        if not items:
            return
        first = _squash(_text(items[0]))
        index = 4 if 'get_node_base_interface' in first and len(items) > 4 else 1
        owner_arg = items[0]
        owner_text = _squash(_text(owner_arg))
        receiver = None if owner_text in ('this', 'shared_from_this()', '*this') or \
            owner_text.startswith(('this->get_node_', 'get_node_')) else owner_text.split('->')[0]
        owner = self.node_for(receiver)
        if owner is None:
            if receiver is not None:
                create = 'create_server' if section == 'action_servers' else 'create_client'
                self.untied(node, f'rclcpp_action::{create}', receiver)
            return
        gaps: list[Gap] = []
        name, gap = self.name_of(items[index] if len(items) > index else None, 'action name', node)
        gaps += [gap] if gap else []
        kind, gap = self.type_of(template, node)
        gaps += [gap] if gap else []
        owner.entities.append(ExtractedEntity(section, name, kind, self.r.loc(node), gaps=gaps))
        self._source(owner)

    def _descriptor(self, arg: Any) -> tuple[_Descriptor | None, Gap | None]:
        value = self.value(arg) if arg.type != 'identifier' or _text(arg) not in self.scope else self.scope[_text(arg)]
        if isinstance(value, _Descriptor):
            return value, None
        if isinstance(value, dict):
            return _Descriptor(value), None
        location = self.r.loc(arg)
        return None, Gap('descriptor', f'the parameter descriptor at {self.r.shown(location)} is {_RUNTIME} '
                         '(read_only, ranges and description unknown)', location, _DEFAULT)

    def _declare_parameter(self, node: Any, function: Any, items: list[Any], record: bool) -> Any:
        receiver, _, template = _split_call(function)
        owner = self.node_for(receiver)
        if owner is None or not items:
            return None
        gaps: list[Gap] = []
        name, gap = self.name_of(items[0], 'parameter name', node)
        gaps += [gap] if gap else []
        kind: str | None = None
        if template is not None and template.named_children:
            kind = _param_type(_squash(_text(template.named_children[0])))
            if kind is None:
                gaps.append(Gap('type', f'the parameter type {_text(template.named_children[0])} at '
                                f'{self.r.shown(self.r.loc(template))} has no NoDL type', self.r.loc(template), _TYPE))
        default: Any = None
        has_default = False
        descriptor_arg = None
        if len(items) > 1:
            second = _squash(_text(items[1]))
            enum = second.rsplit('::', 1)[-1]
            if enum in _PARAM_ENUM:
                kind = _PARAM_ENUM[enum]
                descriptor_arg = items[2] if len(items) > 2 else None
            else:
                value = self.value(items[1])
                descriptor_arg = items[2] if len(items) > 2 else None
                if isinstance(value, (_Unknown, _ParamValue, _Descriptor)) or value is None or isinstance(value, dict):
                    location = self.r.loc(items[1])
                    gaps.append(Gap('default_value', f'the default of parameter {name!r} at '
                                    f'{self.r.shown(location)} is {_RUNTIME}', location, _DEFAULT))
                else:
                    if kind is None:
                        kind = _value_type(value)
                        if kind is None:
                            location = self.r.loc(items[1])
                            gaps.append(Gap('type', f'the type of parameter {name!r} at {self.r.shown(location)} '
                                            'cannot be told from its default (an empty list?)', location, _TYPE))
                    default, has_default = _fit(value, kind), True
        elif template is None:
            gaps.append(Gap('type', f'parameter {name!r} at {self.r.shown(self.r.loc(node))} is declared without '
                            'a type or a default', self.r.loc(node), _TYPE))
        entity = ExtractedEntity(PARAMETERS, name, kind, self.r.loc(node), default_value=default,
                                 has_default=has_default, gaps=gaps)
        if descriptor_arg is not None:
            descriptor, gap = self._descriptor(descriptor_arg)
            if gap is not None:
                entity.gaps.append(gap)
            elif descriptor is not None:
                self._apply_descriptor(entity, descriptor, descriptor_arg)
        if record:
            owner.entities.append(entity)
            self._source(owner)
        if name is not None:
            return _ParamValue(name, default, self.r.loc(node))
        return None

    def _apply_descriptor(self, entity: ExtractedEntity, descriptor: _Descriptor, where: Any) -> None:
        fields = descriptor.fields
        if isinstance(fields.get('description'), (_Unknown, _ParamValue)):
            fields = {k: v for k, v in fields.items() if k != 'description'}  # a comment only
        for key, value in fields.items():
            if key in ('additional_constraints', 'name', 'type', 'dynamic_typing'):
                continue
            if isinstance(value, (_Unknown, _ParamValue)):
                entity.gaps.append(Gap('descriptor', f'the descriptor field {key} at {self.r.shown(self.r.loc(where))} '
                                       f'is {_RUNTIME}', self.r.loc(where), _DEFAULT))
                return
        if fields.get('read_only') is True:
            entity.read_only = True
        if isinstance(fields.get('description'), str) and fields['description']:
            entity.description = fields['description']
        for key in ('floating_point_range', 'integer_range'):
            ranges = fields.get(key)
            if isinstance(ranges, list) and len(ranges) == 1:
                item = ranges[0]
                item = item.fields if isinstance(item, _Descriptor) else item
                if isinstance(item, dict) and 'from_value' in item and 'to_value' in item:
                    entity.validation = {'bounds<>': [item['from_value'], item['to_value']]}

    def _declare_parameters(self, owner: ExtractedNode, node: Any, items: list[Any], template: Any) -> None:
        if len(items) < 2:
            return
        prefix, gap = self.name_of(items[0], 'parameter prefix', node)
        values = self.value(items[1])
        location = self.r.loc(node)
        if gap is not None or not isinstance(values, dict):
            gaps = [gap] if gap is not None else [Gap('name', f'the parameters declared at {self.r.shown(location)} '
                                                      f'come from a map {_RUNTIME}', location, _NAME)]
            owner.entities.append(ExtractedEntity(PARAMETERS, None, None, location, gaps=gaps))
            self._source(owner)
            return
        declared = _param_type(_squash(_text(template.named_children[0]))) if template is not None and \
            template.named_children else None
        for key, value in values.items():
            if isinstance(value, tuple):
                value = value[0]
            kind = declared or _value_type(value)
            full = f'{prefix}.{key}' if prefix else key
            owner.entities.append(ExtractedEntity(PARAMETERS, full, kind, location, default_value=_fit(value, kind),
                                         has_default=True))
        self._source(owner)

    def _image_transport(self, node: Any, topic: Any, method: str) -> None:
        owner = self.node_for(None)
        if owner is None:
            return
        section = 'publishers' if method in ('create_publisher', 'advertise', 'create_camera_publisher',
                                             'advertiseCamera') else 'subscriptions'
        name, _ = self.name_of(topic, 'image topic', node)
        location = self.r.loc(node)
        owner.entities.append(ExtractedEntity(section, name, 'sensor_msgs/msg/Image', location,
                                              helper='image_transport',
                                              gaps=[Gap('entity', f'image_transport at {self.r.shown(location)}: '
                                                        'the topics depend on the transport plug-ins installed '
                                                        'where it runs', location, _PLUGIN)]))
        self._source(owner)

    def helper(self, type_text: str, args: Any, where: Any) -> bool:
        """tf2_ros, diagnostic_updater and message_filters objects: the entities they create."""
        if 'Transform' not in type_text and 'Updater' not in type_text and 'message_filters' not in type_text:
            return False  # none of them (every name _HELPERS knows holds one of these words)
        plain = re.sub(r'^(?:std::)?make_(?:shared|unique)<(.+)>$', r'\1', type_text)
        plain = re.sub(r'<.*>$', '', plain) if not plain.startswith('message_filters') else plain
        short = plain.rsplit('::', 1)[-1] if plain.startswith(('tf2_ros', 'diagnostic_updater')) else plain
        known = short in _HELPERS or plain.startswith('message_filters::Subscriber')
        if not known:
            return False
        items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
        owner_text = _squash(_text(items[0])) if items else ''
        receiver = None if owner_text in ('this', '*this', 'shared_from_this()', '') or owner_text.startswith(
            ('this->get_node_', 'get_node_')) else owner_text.split('->')[0].lstrip('*')
        if short == 'TransformListener' and items and receiver is not None and receiver not in self.scope \
                and (self.klass is None or receiver not in self.klass.members):
            receiver = None if len(items) == 1 else receiver
        if short == 'TransformListener':
            receiver = None if len(items) < 2 else _squash(_text(items[1])).lstrip('*').split('->')[0]
            receiver = None if receiver in ('this', 'shared_from_this()') else receiver
        owner = self.node_for(receiver)
        if owner is None:
            return True
        location = self.r.loc(where)
        if plain.startswith('message_filters::Subscriber'):
            match = re.fullmatch(r'message_filters::Subscriber<(.+?)(?:,.*)?>', plain)
            kind_text = match.group(1) if match else ''
            if len(items) < 2:
                return True
            self._filter(owner, where, kind_text, items[1], items[2] if len(items) > 2 else None)
            return True
        for section, name, kind, qos in _HELPERS[short]:
            owner.entities.append(ExtractedEntity(section, name, kind, location, qos=qos() if qos else None,
                                         has_default=section == PARAMETERS,
                                         default_value=1.0 if section == PARAMETERS else None,
                                         helper=plain))
        self._source(owner)
        return True

    def _filter(self, owner: ExtractedNode, where: Any, kind_text: str, topic: Any, qos_arg: Any) -> None:
        gaps: list[Gap] = []
        name, gap = self.name_of(topic, 'topic name', where)
        gaps += [gap] if gap else []
        kind, gap = self.interface_type(kind_text, where)
        gaps += [gap] if gap else []
        if qos_arg is None:
            qos: Any = qos_of_name('rmw_qos_profile_default')
        else:
            qos, gap = self.qos_of(qos_arg)
            gaps += [gap] if gap else []
        owner.entities.append(ExtractedEntity('subscriptions', name, kind, self.r.loc(where), qos=qos, gaps=gaps,
                                     helper='message_filters::Subscriber'))
        self._source(owner)

    def _filter_subscribe(self, node: Any, items: list[Any], receiver: str) -> None:
        owner = self.node_for(None)
        if owner is None or len(items) < 2:
            return
        self._filter(owner, node, self.filters[receiver], items[1], items[2] if len(items) > 2 else None)


_QOS_METHODS = {'reliable', 'best_effort', 'transient_local', 'durability_volatile', 'keep_last', 'keep_all',
                'reliability', 'durability', 'history', 'liveliness', 'deadline', 'lifespan',
                'liveliness_lease_duration', 'avoid_ros_namespace_conventions', 'reliability_best_available',
                'durability_best_available'}


def _policy(text: str) -> str | None:
    short = text.rsplit('::', 1)[-1]
    match = re.fullmatch(r'RMW_QOS_POLICY_(?:RELIABILITY|DURABILITY|HISTORY|LIVELINESS)_([A-Z_]+)', short)
    if match:
        word = match.group(1)
        return word if word in _POLICY_WORDS.values() or word in ('SYSTEM_DEFAULT', 'BEST_AVAILABLE') else None
    words = {'Reliable': 'RELIABLE', 'BestEffort': 'BEST_EFFORT', 'SystemDefault': 'SYSTEM_DEFAULT',
             'BestAvailable': 'BEST_AVAILABLE', 'TransientLocal': 'TRANSIENT_LOCAL', 'Volatile': 'VOLATILE',
             'KeepLast': 'KEEP_LAST', 'KeepAll': 'KEEP_ALL', 'Automatic': 'AUTOMATIC',
             'ManualByTopic': 'MANUAL_BY_TOPIC'}
    return words.get(short)


def _tf_qos(depth: int, latched: bool) -> Any:
    def make() -> QoSProfile:
        profile = _depth_qos(depth)
        if latched:
            profile.durability = 'TRANSIENT_LOCAL'
        return profile
    return make


#: Helper class -> the entities it creates: (section, name, type, QoS maker).  tf2_ros/qos.hpp:
#: dynamic listener and broadcaster QoS(100); static: QoS(100) (listener) / QoS(1) (broadcaster),
#: transient local.  diagnostic_updater::Updater publishes /diagnostics (depth 1) and declares
#: diagnostic_updater.period (default 1.0 s).
_HELPERS: dict[str, list[tuple[str, str, str | None, Any]]] = {
    'TransformBroadcaster': [('publishers', '/tf', 'tf2_msgs/msg/TFMessage', _tf_qos(100, False))],
    'StaticTransformBroadcaster': [('publishers', '/tf_static', 'tf2_msgs/msg/TFMessage', _tf_qos(1, True))],
    'TransformListener': [('subscriptions', '/tf', 'tf2_msgs/msg/TFMessage', _tf_qos(100, False)),
                          ('subscriptions', '/tf_static', 'tf2_msgs/msg/TFMessage', _tf_qos(100, True))],
    'Updater': [('publishers', '/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray', _tf_qos(1, False)),
                (PARAMETERS, 'diagnostic_updater.period', 'double', None)],
}


def _split_call(function: Any) -> tuple[str | None, str | None, Any]:
    """(receiver, method, template arguments) of a call's function part.

    Receiver: None for an unqualified call (``create_publisher(...)``), ``this`` for
    ``this->...``, the object's text for ``node->...`` / ``node.``, the namespace for
    ``ns::f(...)``.
    """
    template = None
    receiver: str | None = None
    target = function
    if function.type == 'field_expression':
        obj = function.child_by_field_name('argument')
        target = function.child_by_field_name('field')
        receiver = _squash(_text(obj)) if obj is not None else None
        if receiver is not None and (receiver == 'this' or receiver.startswith('this->')):
            receiver = 'this' if receiver == 'this' else receiver[len('this->'):]
        if receiver is not None:
            receiver = re.sub(r'\(\)$', '', receiver) if receiver.endswith(('shared_from_this()',)) else receiver
            if receiver in ('shared_from_this', 'get_node()', 'node()'):
                receiver = 'this'
            receiver = receiver.lstrip('*')
    elif function.type == 'qualified_identifier':
        scope = function.child_by_field_name('scope')
        receiver = _squash(_text(scope)) if scope is not None else None
        target = function.child_by_field_name('name')
        while target is not None and target.type == 'qualified_identifier':
            target = target.child_by_field_name('name')
    if target is None:
        return receiver, None, None
    if target.type in ('template_method', 'template_function'):
        template = target.child_by_field_name('arguments')
        target = target.child_by_field_name('name')
    return receiver, _text(target) if target is not None else None, template


def _member_value(reader: _PackageReader, klass: _Class, name: str, where: Any) -> Any:
    """A member's compile-time value: initialised from a literal (declaration or constructor
    initialiser list) and never assigned in the class's methods; a parameter's value when it is
    assigned once from declare_parameter; otherwise unknown."""
    value_node, qualifiers, location = klass.members[name]
    assigned = _member_assignments(reader, klass, name)
    initial = None
    for definition, file in _class_methods(reader, klass):
        for init in reader.walk(definition, 'field_initializer'):
            target = init.named_children[0] if init.named_children else None
            if target is not None and _text(target) == name:
                args = init.named_children[1] if len(init.named_children) > 1 else None
                items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
                if len(items) == 1:
                    initial = (items[0], file)
    scan = _BodyScan(reader, None)
    if len(assigned) == 1 and initial is None and value_node is None:
        node, file, owner_scan = assigned[0]
        right = node.child_by_field_name('right')
        saved = reader.file
        reader.file = file
        value = owner_scan.value(right) if owner_scan is not None else scan.value(right)
        reader.file = saved
        if isinstance(value, _ParamValue):
            return value
    if assigned:
        node, file, _ = assigned[0]
        return _Unknown(f'assigned at {reader.shown(Location(file, node.start_point[0] + 1, node.start_point[1] + 1))}',
                        reader.loc(where))
    source = initial or ((value_node, klass.file) if value_node is not None else None)
    if source is None:
        return _Unknown(_RUNTIME, reader.loc(where))
    saved = reader.file
    reader.file = source[1]
    value = scan.value(source[0])
    if isinstance(value, _Unknown) and source[0].type == 'initializer_list' and len(source[0].named_children) == 1:
        value = scan.value(source[0].named_children[0])
    reader.file = saved
    return value


def _class_methods(reader: _PackageReader, klass: _Class) -> list[tuple[Any, str]]:
    cache = reader.methods
    if not cache and reader.functions:
        for d, f, owner in reader.functions:
            name = reader.owner_class(owner)
            if name is not None:
                cache.setdefault(name, []).append((d, f))
        cache.setdefault('', [])
    return cache.get(klass.name, [])


def _member_assignments(reader: _PackageReader, klass: _Class, name: str) -> list[tuple[Any, str, Any]]:
    found = []
    for definition, file in _class_methods(reader, klass):
        for node in reader.walk(definition, 'assignment_expression'):
            left = node.child_by_field_name('left')
            if left is None:
                continue
            text = _squash(_text(left))
            if text in (name, f'this->{name}'):
                found.append((node, file, None))
    return found


class _NodeScan(_BodyScan):
    """The methods of one node class."""

    def __init__(self, reader: _PackageReader, klass: _Class, node: ExtractedNode) -> None:
        super().__init__(reader, klass)
        self.node = node
        self.filters = {}

    def node_for(self, receiver: Any) -> ExtractedNode | None:
        if receiver in (None, 'this'):
            return self.node
        return None

    def scan(self) -> None:
        self._node_name()
        if self.klass is not None and self.klass.template_params:
            self.r.report(_TEMPLATE, f'{self.node.name} is a class template: what depends on its parameters '
                          f'({", ".join(sorted(self.klass.template_params))}) is a gap', self.node.location,
                          Severity.INFO)
        assert self.klass is not None
        filters: dict[str, str] = {}
        for declaration in self.r.walk(self.klass.node, 'field_declaration'):
            type_node = declaration.child_by_field_name('type')
            type_text = _squash(_text(type_node)) if type_node is not None else ''
            if type_text.startswith('message_filters::Subscriber<'):
                for declarator in declaration.children_by_field_name('declarator'):
                    name = _declared_name(declarator)
                    if name is not None:
                        filters[name] = re.sub(r'^message_filters::Subscriber<(.+?)(?:,.*)?>$', r'\1', type_text)
        for definition, file in _class_methods(self.r, self.klass):
            self.r.file = file
            self.scope = {}
            self.filters = dict(filters)
            for child in definition.named_children:
                if child.type == 'field_initializer_list':
                    for init in child.named_children:
                        self._member_init(init)
            body = definition.child_by_field_name('body')
            if body is not None and _CANDIDATE.search(body.text) is not None:
                self.visit(body)  # a body with no candidate call creates nothing: not walked

    def _member_init(self, init: Any) -> None:
        if not init.named_children:
            return
        target = init.named_children[0]
        args = init.named_children[1] if len(init.named_children) > 1 else None
        assert self.klass is not None
        member = self.klass.members.get(_text(target))
        if member is None or args is None:
            return
        type_text = ''
        field_decl = member[2]
        for declaration in self.r.walk(self.klass.node, 'field_declaration'):
            if declaration.start_point[0] + 1 == field_decl.line:
                type_node = declaration.child_by_field_name('type')
                type_text = _squash(_text(type_node)) if type_node is not None else ''
        if type_text.startswith('message_filters::Subscriber'):
            self.filters[_text(target)] = re.sub(r'^message_filters::Subscriber<(.+?)(?:,.*)?>$', r'\1', type_text)
            items = [a for a in args.named_children if a.type != 'comment']
            if len(items) >= 2:
                self.helper(type_text, args, init)
            return
        self.helper(type_text, args, init)
        self.visit(args)

    def _node_name(self) -> None:
        assert self.klass is not None
        bases = {re.sub(r'<.*>', '', b) for b in self.klass.bases}
        short = {b.rsplit('::', 1)[-1] for b in bases}
        for definition, file in _class_methods(self.r, self.klass):
            for init in self.r.walk(definition, 'field_initializer'):
                if not init.named_children:
                    continue
                target = _squash(_text(init.named_children[0]))
                if target not in bases and target not in short and target not in _NODE_BASES:
                    continue
                args = init.named_children[1] if len(init.named_children) > 1 else None
                items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
                if not items:
                    return
                self.r.file = file
                value = self.value(items[0])
                if isinstance(value, str):
                    self.node.node_name = value
                    return
                param = _parameter_index(definition, _squash(_text(items[0])))
                if param is not None:
                    made = [v for v in (self._made(param)) if isinstance(v, str)]
                    if len(set(made)) == 1:
                        self.node.node_name = made[0]
                        return
                location = self.r.loc(items[0])
                self.node.notes.append(Diagnostic(Severity.INFO, f'the node name of {self.node.name} at '
                                                  f'{self.r.shown(location)} is {_RUNTIME}', file=location.file,
                                                  line=location.line, column=location.column, code=_NODE_NAME))
                return

    def _made(self, index: int) -> list[Any]:
        out = []
        assert self.klass is not None
        for cls, places in self.r.instantiations.items():
            if cls != self.klass.name and cls.rsplit('::', 1)[-1] != self.klass.name.rsplit('::', 1)[-1]:
                continue
            for file, args in places:
                items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
                if len(items) > index:
                    saved = self.r.file
                    self.r.file = file
                    out.append(_BodyScan(self.r, None).value(items[index]))
                    self.r.file = saved
        return out


def _parameter_index(definition: Any, name: str) -> int | None:
    declarator = definition.child_by_field_name('declarator')
    params = declarator.child_by_field_name('parameters') if declarator is not None else None
    if params is None:
        return None
    for index, param in enumerate(p for p in params.named_children if p.type != 'comment'):
        if _declared_name(param.child_by_field_name('declarator')) == name if \
                param.child_by_field_name('declarator') is not None else False:
            return index
    return None


class _FreeScan(_BodyScan):
    """A function that is not a node's method: a node it makes itself (``auto node =
    rclcpp::Node::make_shared("talker")``) is a node of its own."""

    def __init__(self, reader: _PackageReader, definition: Any, out: list[ExtractedNode], package: str | None) -> None:
        super().__init__(reader, None)
        self.definition = definition
        self.out = out
        self.package = package

    def node_for(self, receiver: Any) -> ExtractedNode | None:
        if receiver is None:
            return None
        value = self.scope.get(receiver)
        return value.node if isinstance(value, _NodeRef) else None

    def scan(self) -> None:
        body = self.definition.child_by_field_name('body')
        if body is not None and any(word.encode() in body.text for word in ('Node', 'LifecycleNode')):
            self.visit(body)

    def value(self, node: Any) -> Any:
        if node is not None and node.type == 'call_expression':
            function = node.child_by_field_name('function')
            text = _squash(_text(function)) if function is not None else ''
            base = None
            if (re.fullmatch(r'(?:std::)?make_shared<(rclcpp::Node|rclcpp_lifecycle::LifecycleNode)>', text)
                    or re.fullmatch(r'(rclcpp::Node|rclcpp_lifecycle::LifecycleNode)::make_shared', text)):
                base = text
            if base is not None:
                args = node.child_by_field_name('arguments')
                items = [a for a in args.named_children if a.type != 'comment'] if args is not None else []
                name = super().value(items[0]) if items else None
                location = self.r.loc(node)
                made = ExtractedNode(name=name if isinstance(name, str) else f'node at {self.r.shown(location)}',
                                     location=location, language='cpp',
                                     base='lifecycle_node' if 'Lifecycle' in base else 'node',
                                     package=self.package, node_name=name if isinstance(name, str) else None)
                made.sources.append(self.r.file)
                if not isinstance(name, str):
                    made.notes.append(Diagnostic(Severity.INFO, f'the node name at {self.r.shown(location)} is '
                                                 f'{_RUNTIME}', file=location.file, line=location.line,
                                                 column=location.column, code=_NODE_NAME))
                self.out.append(made)
                return _NodeRef(made)
        return super().value(node)


# ----------------------------------------------------------------------------- entry points


def _sources(paths: Iterable[str], reader: _PackageReader) -> list[str]:
    out: list[str] = []
    for path in paths:
        if os.path.isdir(path):
            for root, dirs, files in os.walk(path):
                dirs[:] = sorted(d for d in dirs if not d.startswith('.') and d not in ('build', 'install', 'log'))
                out += [os.path.join(root, f) for f in sorted(files) if f.endswith(CPP_SUFFIXES)]
        elif os.path.exists(path) or os.path.islink(path):
            out.append(path)
        else:
            reader.report(_UNREADABLE, 'no such file or folder', Location(path), Severity.ERROR)
    return out


def extract_cpp(paths: Iterable[str], *, package: str | None = None, targets: CMakeTargets | None = None,
                relative_to: str | None = None) -> Extraction:
    """Extract the rclcpp nodes of the C++ sources ``paths`` (files, or folders searched for
    ``.cpp``/``.hpp``... files) read together, as one package's sources.

    ``targets`` (from :func:`nodl.extract.cmake.read_cmake`) maps node classes to
    executables; ``relative_to`` shortens the paths shown in messages.  Never raises for bad
    input: each problem is a located diagnostic of the returned :class:`Extraction`.
    """
    reader = _PackageReader(relative_to)
    files = _sources(paths, reader)
    try:
        parser = cpp_parser()
    except ImportError:
        reader.report(_NOT_INSTALLED, 'reading C++ needs the tree-sitter C++ parser: pip install '
                      "'nodl-toolkit[extract]'", Location(files[0] if files else '<c++>'), Severity.ERROR)
        return reader.extraction
    for path in files:
        reader.add_file(path, parser)
    return reader.run(targets, package if targets is None or targets.package is None else targets.package)


def extract_cpp_package(folder: str, *, relative_to: str | None = None) -> Extraction:
    """Extract the rclcpp nodes of the package in ``folder``: its CMakeLists.txt (when there is
    one) maps classes to executables, and every C++ source below the folder is read."""
    from nodl.extract.cmake import read_cmake

    cmake = os.path.join(folder, 'CMakeLists.txt')
    targets = None
    pre: list[Diagnostic] = []
    if os.path.exists(cmake):
        targets = read_cmake(cmake)
        pre = list(targets.diagnostics)
    extraction = extract_cpp([folder], targets=targets, relative_to=relative_to)
    extraction.diagnostics = pre + extraction.diagnostics
    if os.path.exists(cmake):
        extraction.files.insert(0, cmake)
    return extraction
