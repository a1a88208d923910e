"""Which executables a C++ package builds from which sources: a reader of CMakeLists.txt.

Nothing is configured or run.  The commands of CMakeLists.txt are read in order with the
variables they set (``set``, ``list(APPEND)``, ``project``), the functions and macros the file
defines (with ``cmake_parse_arguments``), ``foreach`` loops and the branches of ``if`` (a
variable set differently in two branches keeps every value: the node may be built from
either source).  What it records:

* ``add_executable`` / ``ament_auto_add_executable`` and ``add_library`` /
  ``ament_auto_add_library`` with their sources (``target_sources`` adds more), and an
  executable's ``OUTPUT_NAME`` (``set_target_properties``);
* ``rclcpp_components_register_node(LIB PLUGIN CLASS EXECUTABLE EXE)``: a component with an
  executable of its own; ``rclcpp_components_register_nodes(LIB CLASS...)``: components only;
* ``install(PROGRAMS file... DESTINATION lib/${PROJECT_NAME} [RENAME name])``: scripts (Python
  nodes of an ament_cmake_python package) installed where ``ros2 run`` finds them.

A command that cannot be read, or a source path that depends on something this reader cannot
know (an undefined variable, the build tree), is one located diagnostic; the rest is read.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['CMakeTargets', 'CMakeCommand', 'parse_cmake', 'read_cmake', 'read_cmake_text']

_SYNTAX = 'NODL945'
_UNKNOWN = 'NODL946'
_UNREADABLE = 'NODL931'

#: Limits that keep a hostile file bounded: commands run (loops and calls included), nesting.
MAX_COMMANDS = 100_000
MAX_DEPTH = 32
_ALTERNATIVES = 16


@dataclass(frozen=True, slots=True)
class CMakeCommand:
    """One command invocation: its name (lower case), its arguments and where it is."""

    name: str
    args: tuple[tuple[str, bool], ...]   # (text, quoted)
    line: int
    column: int


@dataclass(slots=True)
class CMakeTargets:
    """What a CMakeLists.txt builds: executables and libraries with their sources (absolute
    paths), and the rclcpp components registered."""

    file: str
    package: str | None = None
    executables: dict[str, list[str]] = field(default_factory=dict)
    libraries: dict[str, list[str]] = field(default_factory=dict)
    #: Installed name of an executable target (OUTPUT_NAME), when it differs from the target's.
    output_names: dict[str, str] = field(default_factory=dict)
    #: Component class -> (library, executable or None).
    plugins: dict[str, tuple[str, str | None]] = field(default_factory=dict)
    #: Scripts installed into ``lib/<package>`` (``install(PROGRAMS)``): executable -> source.
    programs: dict[str, str] = field(default_factory=dict)
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def executable_name(self, target: str) -> str:
        """The name an executable target is installed as."""
        return self.output_names.get(target, target)

    def executable_of_plugin(self, cls: str) -> str | None:
        """The executable ``rclcpp_components_register_node`` gives the component ``cls``."""
        found = self.plugins.get(cls.lstrip(':'))
        return found[1] if found is not None else None

    def library_of_plugin(self, cls: str) -> str | None:
        """The library the component ``cls`` is registered from (None: not a component)."""
        found = self.plugins.get(cls.lstrip(':'))
        return found[0] if found is not None else None

    def executable_of_sources(self, files: set[str] | list[str]) -> str | None:
        """The executable built from one of ``files`` (the first, in file order), if any."""
        wanted = {os.path.realpath(f) for f in files}
        for target, sources in self.executables.items():
            if wanted & {os.path.realpath(s) for s in sources}:
                return self.executable_name(target)
        return None


_TOKEN = re.compile(r'''
    (?P<space>[ \t\r]+)
  | (?P<newline>\n)
  | (?P<comment>\#\[(?P<ceq>=*)\[.*?\](?P=ceq)\]|\#[^\n]*)
  | (?P<bracket>\[(?P<beq>=*)\[.*?\](?P=beq)\])
  | (?P<quoted>"(?:[^"\\]|\\.)*")
  | (?P<open>\()
  | (?P<close>\))
  | (?P<word>(?:[^\s()#"\\]|\\.)+)
''', re.VERBOSE | re.DOTALL)
_IDENT = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')


def parse_cmake(text: str, file: str) -> tuple[list[CMakeCommand], list[Diagnostic]]:
    """The commands of a CMake file, and a diagnostic for what cannot be read."""
    commands: list[CMakeCommand] = []
    problems: list[Diagnostic] = []
    pos, line, line_start = 0, 1, 0
    length = len(text)

    def where(at: int) -> tuple[int, int]:
        return text.count('\n', 0, at) + 1, at - (text.rfind('\n', 0, at) + 1) + 1

    while pos < length:
        match = _TOKEN.match(text, pos)
        if match is None:
            ln, col = where(pos)
            problems.append(Diagnostic(Severity.WARNING, 'CMakeLists.txt cannot be read from here on '
                                       '(an unterminated string or bracket?)', file=file, line=ln,
                                       column=col, code=_SYNTAX))
            break
        kind = match.lastgroup
        if kind in ('space', 'newline', 'comment'):
            pos = match.end()
            continue
        if kind != 'word' or not _IDENT.fullmatch(match.group()):
            ln, col = where(pos)
            problems.append(Diagnostic(Severity.WARNING, f'expected a command here, found {match.group()[:20]!r}; '
                                       'skipped to the next line', file=file, line=ln, column=col, code=_SYNTAX))
            nxt = text.find('\n', pos)
            pos = length if nxt < 0 else nxt + 1
            continue
        name = match.group()
        start = pos
        pos = match.end()
        while pos < length and text[pos] in ' \t':
            pos += 1
        if pos >= length or text[pos] != '(':
            ln, col = where(start)
            problems.append(Diagnostic(Severity.WARNING, f'{name} is not followed by "("; skipped', file=file,
                                       line=ln, column=col, code=_SYNTAX))
            continue
        pos += 1
        depth = 1
        args: list[tuple[str, bool]] = []
        while pos < length and depth:
            token = _TOKEN.match(text, pos)
            if token is None:
                break
            kind = token.lastgroup
            value = token.group()
            pos = token.end()
            if kind in ('space', 'newline', 'comment'):
                continue
            if kind == 'open':
                depth += 1
                args.append(('(', False))
            elif kind == 'close':
                depth -= 1
                if depth:
                    args.append((')', False))
            elif kind == 'quoted':
                args.append((value[1:-1], True))
            elif kind == 'bracket':
                inner = value[value.index('[', 1) + 1:value.rindex(']', 0, len(value) - 1)]
                args.append((inner.lstrip('\n'), True))
            else:
                args.append((value, False))
        ln, col = where(start)
        if depth:
            problems.append(Diagnostic(Severity.WARNING, f'the arguments of {name} are not closed with ")"; '
                                       'the rest of CMakeLists.txt is not read', file=file, line=ln,
                                       column=col, code=_SYNTAX))
            break
        commands.append(CMakeCommand(name.lower(), tuple(args), ln, col))
    del line, line_start
    return commands, problems


@dataclass(slots=True)
class _Function:
    params: list[str]
    body: list[CMakeCommand]
    macro: bool


class _Evaluator:
    def __init__(self, file: str, targets: CMakeTargets) -> None:
        self.file = file
        self.folder = os.path.dirname(os.path.abspath(file))
        self.targets = targets
        self.functions: dict[str, _Function] = {}
        self.count = 0
        self.reported: set[tuple[int, int]] = set()

    def problem(self, command: CMakeCommand, message: str) -> None:
        if (command.line, command.column) in self.reported:
            return
        self.reported.add((command.line, command.column))
        self.targets.diagnostics.append(Diagnostic(Severity.WARNING, message, file=self.file, line=command.line,
                                                   column=command.column, code=_UNKNOWN))

    # -- values: each variable holds its possible values (more than one after if/else)
    def expand(self, text: str, scope: dict[str, list[str]]) -> list[str]:
        results = [text]
        for _ in range(32):
            done = True
            out: list[str] = []
            for value in results:
                match = re.search(r'\$\{([^${}]*)\}', value)
                if match is None:
                    out.append(value)
                    continue
                done = False
                name = match.group(1)
                options = scope.get(name)
                if options is None:
                    options = [os.environ.get(name[4:-1], '')] if name.startswith('ENV{') else ['\0']
                for option in options[:_ALTERNATIVES]:
                    out.append(value[:match.start()] + option + value[match.end():])
            results = out[:_ALTERNATIVES]
            if done:
                break
        return results

    def arguments(self, command: CMakeCommand, scope: dict[str, list[str]]) -> list[list[str]]:
        """Each argument's values after expansion; unquoted ones split on ';'.  Returns a list of
        alternatives per argument position (most commands have one alternative)."""
        out: list[list[str]] = []
        for text, quoted in command.args:
            values = self.expand(text, scope)
            if quoted:
                out.append(values)
                continue
            split = [v.split(';') for v in values]
            if len(split) == 1:
                out += [[item] for item in split[0] if item != '']
            else:  # alternatives: keep each alternative's items together as candidates
                width = max(len(s) for s in split)
                for index in range(width):
                    out.append(sorted({s[index] for s in split if index < len(s)}))
        return out

    def run(self, commands: list[CMakeCommand], scope: dict[str, list[str]], depth: int = 0,
            conditional: int = 0) -> None:
        index = 0
        while index < len(commands):
            command = commands[index]
            self.count += 1
            if self.count > MAX_COMMANDS or depth > MAX_DEPTH:
                self.problem(command, f'CMakeLists.txt runs more than {MAX_COMMANDS} commands (or nests calls '
                             f'{MAX_DEPTH} deep); the rest is not read')
                return
            name = command.name
            if name in ('function', 'macro'):
                end = self.block_end(commands, index, name, f'end{name}')
                args = [a for a, _ in command.args]
                if args:
                    self.functions[args[0].lower()] = _Function(args[1:], commands[index + 1:end], name == 'macro')
                index = end + 1
                continue
            if name == 'foreach':
                end = self.block_end(commands, index, 'foreach', 'endforeach')
                self.foreach(command, commands[index + 1:end], scope, depth, conditional)
                index = end + 1
                continue
            if name == 'while':
                end = self.block_end(commands, index, 'while', 'endwhile')
                self.problem(command, 'a while() loop is not run by the extraction; what it builds is not mapped')
                index = end + 1
                continue
            if name == 'if':
                end = self.block_end(commands, index, 'if', 'endif')
                self.run(commands[index + 1:end], scope, depth, conditional + 1)
                index = end + 1
                continue
            if name in ('else', 'elseif', 'endif', 'endfunction', 'endmacro', 'endforeach', 'endwhile'):
                index += 1
                continue
            self.command(command, scope, depth, conditional)
            index += 1

    def block_end(self, commands: list[CMakeCommand], start: int, opener: str, closer: str) -> int:
        depth = 0
        for index in range(start, len(commands)):
            if commands[index].name == opener:
                depth += 1
            elif commands[index].name == closer:
                depth -= 1
                if depth == 0:
                    return index
        return len(commands)

    def foreach(self, command: CMakeCommand, body: list[CMakeCommand], scope: dict[str, list[str]], depth: int,
                conditional: int) -> None:
        args = [v[0] for v in self.arguments(command, scope)]
        if not args:
            return
        var, rest = args[0], args[1:]
        items: list[str] = []
        if rest[:1] == ['RANGE']:
            numbers = [int(a) for a in rest[1:] if re.fullmatch(r'-?[0-9]+', a)]
            if len(numbers) == 1:
                items = [str(i) for i in range(numbers[0] + 1)]
            elif len(numbers) >= 2:
                items = [str(i) for i in range(numbers[0], numbers[1] + 1, numbers[2] if len(numbers) > 2 else 1)]
        elif rest[:1] == ['IN']:
            mode = None
            for item in rest[1:]:
                if item in ('LISTS', 'ITEMS', 'ZIP_LISTS'):
                    mode = item
                elif mode == 'LISTS':
                    items += [i for v in scope.get(item, [''])[:1] for i in v.split(';') if i]
                elif mode == 'ITEMS':
                    items.append(item)
        else:
            items = rest
        for item in items[:1000]:
            scope[var] = [item]
            self.run(body, scope, depth + 1, conditional)

    def set_var(self, scope: dict[str, list[str]], name: str, value: str, conditional: int) -> None:
        if conditional and name in scope and value not in scope[name]:
            scope[name] = (scope[name] + [value])[:_ALTERNATIVES]
        else:
            scope[name] = [value]

    def command(self, command: CMakeCommand, scope: dict[str, list[str]], depth: int, conditional: int) -> None:
        name = command.name
        if name in self.functions:
            self.call(self.functions[name], command, scope, depth)
            return
        args = self.arguments(command, scope)
        first = [a[0] for a in args]
        if name == 'project' and first:
            scope['PROJECT_NAME'] = [first[0]]
            if self.targets.package is None:
                self.targets.package = first[0]
        elif name == 'set' and first:
            values = [a for a in args[1:]]
            for flag in ('PARENT_SCOPE',):
                if values and values[-1] == [flag]:
                    values = values[:-1]
            if values and values[-1] in (['FORCE'],):
                values = values[:-1]
            if 'CACHE' in [v[0] for v in values]:
                values = values[:[v[0] for v in values].index('CACHE')]
                if first[0] in scope:
                    return
            self.set_var(scope, first[0], ';'.join(v[0] for v in values), conditional)
            if any(len(v) > 1 for v in values):
                for v in values:
                    for alt in v[1:]:
                        self.set_var(scope, first[0], ';'.join(alt if x is v else x[0] for x in values), 1)
        elif name == 'unset' and first:
            scope.pop(first[0], None)
        elif name == 'list' and len(first) >= 2 and first[0] in ('APPEND', 'PREPEND'):
            old = scope.get(first[1], [''])[0]
            new = [x for x in first[2:]]
            joined = ';'.join(([old] if old else []) + new) if first[0] == 'APPEND' else \
                ';'.join(new + ([old] if old else []))
            scope[first[1]] = [joined]
        elif name == 'cmake_parse_arguments':
            self.parse_arguments(first, scope)
        elif name in ('add_executable', 'ament_auto_add_executable'):
            self.target(command, args, self.targets.executables)
        elif name in ('add_library', 'ament_auto_add_library'):
            self.target(command, args, self.targets.libraries)
        elif name == 'target_sources' and first:
            table = self.targets.executables if first[0] in self.targets.executables else \
                self.targets.libraries if first[0] in self.targets.libraries else None
            if table is not None:
                table[first[0]] += self.sources(command, [a for a in args[1:]
                                                          if a[0] not in ('PRIVATE', 'PUBLIC', 'INTERFACE')])
        elif name == 'set_target_properties' and first:
            if 'PROPERTIES' in first:
                at = first.index('PROPERTIES')
                pairs = first[at + 1:]
                for key, value in zip(pairs[::2], pairs[1::2], strict=False):
                    if key == 'OUTPUT_NAME':
                        for target in first[:at]:
                            self.targets.output_names[target] = value
        elif name == 'rclcpp_components_register_node' and first:
            self.register_node(command, first)
        elif name == 'install' and first[:1] == ['PROGRAMS']:
            self.install_programs(command, first[1:], scope)
        elif name == 'rclcpp_components_register_nodes' and first:
            for cls in first[1:]:
                if cls.startswith('RESOURCE_INDEX'):
                    break
                self.targets.plugins.setdefault(cls.lstrip(':'), (first[0], None))

    def install_programs(self, command: CMakeCommand, args: list[str], scope: dict[str, list[str]]) -> None:
        """``install(PROGRAMS file... DESTINATION lib/<package> [RENAME name])``: executables
        ``ros2 run`` finds (other destinations are not executables of the package)."""
        keywords = ('DESTINATION', 'PERMISSIONS', 'CONFIGURATIONS', 'COMPONENT', 'RENAME', 'OPTIONAL',
                    'EXCLUDE_FROM_ALL')
        files: list[str] = []
        options: dict[str, str] = {}
        current = None
        for item in args:
            if item in keywords:
                current = item
            elif current is None:
                files.append(item)
            elif current in ('DESTINATION', 'RENAME') and current not in options:
                options[current] = item
        project = (scope.get('PROJECT_NAME') or [self.targets.package or ''])[0]
        destination = options.get('DESTINATION', '').rstrip('/')
        if '\0' in destination:
            self.problem(command, 'the DESTINATION of install(PROGRAMS) is not known here; its scripts are '
                         'not mapped to executables')
            return
        if not project or destination != f'lib/{project}':
            return
        for source in files:
            if '\0' in source or source.startswith('$<'):
                self.problem(command, 'a file of install(PROGRAMS) uses a variable not known here; it is not '
                             'mapped to an executable')
                continue
            path = os.path.normpath(source if os.path.isabs(source) else os.path.join(self.folder, source))
            name = options['RENAME'] if 'RENAME' in options and len(files) == 1 else os.path.basename(path)
            self.targets.programs[name] = path

    def register_node(self, command: CMakeCommand, first: list[str]) -> None:
        library = first[0]
        keys: dict[str, str | None] = {'PLUGIN': None, 'EXECUTABLE': None, 'EXECUTOR': None,
                                       'RESOURCE_INDEX': None}
        current = None
        for item in first[1:]:
            if item in keys:
                current = item
            elif current is not None:
                keys[current] = item
                current = None
        plugin, executable = keys['PLUGIN'], keys['EXECUTABLE']
        if plugin is None or '\0' in plugin:
            self.problem(command, 'the PLUGIN of rclcpp_components_register_node is not known here')
            return
        if executable is not None and '\0' in executable:
            self.problem(command, f'the EXECUTABLE of component {plugin} is not known here')
            executable = None
        self.targets.plugins[plugin.lstrip(':')] = (library, executable)

    def parse_arguments(self, first: list[str], scope: dict[str, list[str]]) -> None:
        if first[:1] == ['PARSE_ARGV'] and len(first) >= 5:
            start = int(first[1]) if first[1].isdigit() else 0
            prefix, options, one, multi = first[2:6] if len(first) >= 6 else (*first[2:5], '')
            values = scope.get('ARGV', [''])[0].split(';')[start:]
        elif len(first) >= 4:
            prefix, options, one, multi = first[0], first[1], first[2], first[3]
            values = first[4:]
        else:
            return
        option_set = [o for o in options.split(';') if o]
        one_set = [o for o in one.split(';') if o]
        multi_set = [o for o in multi.split(';') if o]
        parsed: dict[str, list[str]] = {}
        unparsed: list[str] = []
        current = None
        for value in values:
            if value in option_set:
                parsed[value] = ['TRUE']
                current = None
            elif value in one_set or value in multi_set:
                current = value
                parsed[value] = []
            elif current is not None:
                parsed[current].append(value)
                if current in one_set:
                    current = None
            else:
                unparsed.append(value)
        for key in option_set + one_set + multi_set:
            scope[f'{prefix}_{key}'] = [';'.join(parsed[key])] if key in parsed else \
                (['FALSE'] if key in option_set else [''])
        scope[f'{prefix}_UNPARSED_ARGUMENTS'] = [';'.join(unparsed)]

    def call(self, function: _Function, command: CMakeCommand, scope: dict[str, list[str]], depth: int) -> None:
        values = [a[0] for a in self.arguments(command, scope)]
        inner = dict(scope)
        for index, param in enumerate(function.params):
            inner[param] = [values[index] if index < len(values) else '']
        inner['ARGN'] = [';'.join(values[len(function.params):])]
        inner['ARGV'] = [';'.join(values)]
        inner['ARGC'] = [str(len(values))]
        for index, item in enumerate(values):
            inner[f'ARGV{index}'] = [item]
        self.run(function.body, inner, depth + 1)
        if function.macro:
            for key, value in inner.items():
                if not key.startswith('ARG'):
                    scope[key] = value

    def target(self, command: CMakeCommand, args: list[list[str]], table: dict[str, list[str]]) -> None:
        if not args:
            return
        names = args[0]
        if len(names) != 1 or '\0' in names[0]:
            self.problem(command, f'the target name of {command.name} is not known here')
            return
        rest = args[1:]
        if rest and rest[0][0] in ('IMPORTED', 'ALIAS'):
            return
        rest = [a for a in rest if a[0] not in ('WIN32', 'MACOSX_BUNDLE', 'EXCLUDE_FROM_ALL', 'STATIC',
                                                 'SHARED', 'MODULE', 'OBJECT', 'INTERFACE', 'DIRECTORY')]
        table.setdefault(names[0], [])
        table[names[0]] += self.sources(command, rest)

    def sources(self, command: CMakeCommand, args: list[list[str]]) -> list[str]:
        out: list[str] = []
        for alternatives in args:
            for value in alternatives:
                if value.startswith('$<'):
                    continue
                if '\0' in value:
                    self.problem(command, f'a source of {command.name} uses a variable not known here; that '
                                 'source is not mapped to its target')
                    continue
                path = value if os.path.isabs(value) else os.path.join(self.folder, value)
                out.append(os.path.normpath(path))
                if not os.path.splitext(path)[1]:  # CMake tries the usual suffixes
                    out += [os.path.normpath(path + suffix) for suffix in ('.cpp', '.cc', '.cxx')]
        return out


def read_cmake_text(text: str, file: str) -> CMakeTargets:
    """What the CMakeLists.txt ``text`` (at path ``file``) builds."""
    targets = CMakeTargets(file=file)
    commands, problems = parse_cmake(text, file)
    targets.diagnostics += problems
    folder = os.path.dirname(os.path.abspath(file))
    scope = {'CMAKE_CURRENT_SOURCE_DIR': [folder], 'CMAKE_SOURCE_DIR': [folder],
             'PROJECT_SOURCE_DIR': [folder], 'CMAKE_CURRENT_LIST_DIR': [folder]}
    _Evaluator(file, targets).run(commands, scope)
    return targets


def read_cmake(path: str) -> CMakeTargets:
    """What the CMakeLists.txt at ``path`` builds; a file that cannot be read is one diagnostic."""
    try:
        with open(path, 'rb') as handle:
            data = handle.read(4 * 1024 * 1024 + 1)
    except OSError as error:
        from nodl.files import describe_os_error

        targets = CMakeTargets(file=path)
        targets.diagnostics.append(Diagnostic(Severity.ERROR, f'cannot read CMakeLists.txt: '
                                              f'{describe_os_error(error)}', file=path, code=_UNREADABLE))
        return targets
    if len(data) > 4 * 1024 * 1024:
        targets = CMakeTargets(file=path)
        targets.diagnostics.append(Diagnostic(Severity.WARNING, 'CMakeLists.txt is larger than 4 MiB; not read',
                                              file=path, line=1, column=1, code=_SYNTAX))
        return targets
    return read_cmake_text(data.decode('utf-8', 'replace'), path)
