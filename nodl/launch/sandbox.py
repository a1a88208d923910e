"""The Python code of a launch (Python launch files, ``$(eval)``) run in a child under limits.

Reading a Python launch file means running it, as ``ros2 launch`` does; so does
``$(eval EXPR)``.  :func:`contained` runs a launch walk so that no such code runs in the
analyser's own process:

* The walk starts in the calling process.  A launch with no Python code (XML and YAML
  without ``$(eval)``) is read there and nothing is forked.
* The first time Python code is about to run (:func:`admit`), the walk stops
  (:class:`NeedsSandbox`) and starts again in a child forked from the running process (no
  new interpreter: the toolkit is already loaded).  The child, in its own process group,
  with standard input from ``/dev/null``, no core dumps, an address-space limit of
  ``memory_mib`` beyond what the analyser already maps and a CPU-time limit, walks the
  whole launch and sends its :class:`~nodl.launch.model.LaunchResult` back through a
  pipe, pickled; the parent unpickles only the launch model's own classes and at most
  :data:`MAX_RESULT_BYTES`.
* The parent holds the wall-clock limit (``timeout``: for all the launch's code together)
  and kills the child's process group when it is over.  The child says which Python code
  it is in (:func:`running`); a child that ends without a result (``os._exit()``, a crash
  by a signal), runs out of time or of memory is blamed on the innermost code it was in,
  and the walk starts again in a new child with that code not run but reported where it is
  included (or its ``$(eval)`` written): the rest of the launch is still read.  After
  :data:`MAX_ATTEMPTS` failures, or once the time is spent, the walk is finished in the
  calling process with no more code run, each refused piece reported.
* With ``execute`` false (``--no-exec``) no code runs at all: a Python launch file is one
  NODL525 error where it is included, an ``$(eval)`` a NODL526 warning (its value unknown,
  as other run-time values are).  ``$(command)`` never runs, in any mode.

Forking a process that runs threads (an rclpy executor) can leave the child holding a
lock another thread held: the verbs that read launch files start no threads before they
read them; a program that does should read its launch files first.
"""

from __future__ import annotations

import contextlib
import gc
import io
import os
import pickle
import signal
import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

from nodl.diagnostics import Severity
from nodl.launch.model import SourceLocation
from nodl.vocabulary import LAUNCH_CODE_MEMORY_MIB, LAUNCH_CODE_TIMEOUT

if TYPE_CHECKING:
    from nodl.launch.model import LaunchResult

__all__ = ['LaunchLimits', 'Refusal', 'NeedsSandbox', 'DEFAULT_TIMEOUT', 'DEFAULT_MEMORY_MIB',
           'MAX_RESULT_BYTES', 'MAX_ATTEMPTS', 'contained', 'admit', 'running', 'python_expression',
           'memory_problem']

#: Seconds the Python code of one launch may run in all (``--launch-timeout``; a fact of
#: :mod:`nodl.vocabulary`, which the command line reads without importing the launch reader).
DEFAULT_TIMEOUT = LAUNCH_CODE_TIMEOUT
#: MiB of memory the Python code of a launch may take (``--launch-memory``).
DEFAULT_MEMORY_MIB = LAUNCH_CODE_MEMORY_MIB
#: The largest result a child may send back.
MAX_RESULT_BYTES = 256 * 1024 * 1024
#: At most this many children per launch (each failure starts one more without the culprit).
MAX_ATTEMPTS = 5
_MIB = 1024 * 1024


class LaunchLimits(NamedTuple):
    """What the Python code of a launch may do: run at all (``execute``, false for
    ``--no-exec``), for how many seconds in all (``timeout``) and with how many MiB beyond
    the analyser's own (``memory_mib``)."""

    execute: bool = True
    timeout: float = DEFAULT_TIMEOUT
    memory_mib: float = DEFAULT_MEMORY_MIB


class Refusal(NamedTuple):
    """Why a piece of Python code is not run: the diagnostic's code, message and severity."""

    code: str
    message: str
    severity: Severity = Severity.ERROR


class NeedsSandbox(BaseException):
    """Python code is about to run in the analyser's own process: the walk starts again in
    a child.  (A BaseException: no ``except Exception`` of the walk or of user code keeps it.)"""


class _Failure(NamedTuple):
    key: str
    what: str
    where: SourceLocation
    refusal: Refusal


class _Session:
    """The state of one :func:`contained` walk (in the parent, then copied into each child)."""

    def __init__(self, limits: LaunchLimits) -> None:
        self.limits = limits
        self.in_child = False
        self.channel: int | None = None
        self.poisoned: dict[str, Refusal] = {}
        self.spent: Refusal | None = None
        self.met: set[str] = set()


_SESSION: _Session | None = None


def _missing(kind: str) -> str:
    return ('; nodes that depend on its value may be missing from the analysis' if kind == 'eval'
            else '; the nodes it would start are missing from the analysis')


def admit(kind: str, key: str, what: str) -> Refusal | None:
    """May the Python code ``what`` (``kind`` ``file`` or ``eval``; ``key`` names it across
    attempts) run now?  None: yes, here.  A :class:`Refusal`: it is not run, say why.

    Raises :class:`NeedsSandbox` when it would run in the analyser's own process.  Outside
    :func:`contained` (the reader used on its own) code runs in the calling process.
    """
    session = _SESSION
    if session is None:
        return None
    if not session.limits.execute:
        if kind == 'eval':
            return Refusal('NODL526', f'{what} is not evaluated: --no-exec is set and it is Python '
                           'code; its value is unknown here (it is known when the launch runs)',
                           Severity.WARNING)
        return Refusal('NODL525', f'{what} is not run: --no-exec is set and reading a Python launch '
                       'file runs its code' + _missing(kind) + ' (analyse it without --no-exec, '
                       'where its code may run)')
    if key in session.poisoned:
        session.met.add(key)
        return session.poisoned[key]
    if session.spent is not None:
        session.met.add('')  # the failure outside any code is said here
        code, message, severity = session.spent
        return Refusal(code, f'{what} is not run: {message}' + _missing(kind), severity)
    if not session.in_child:
        raise NeedsSandbox()
    return None


class _Running:
    """The context manager :func:`running` returns."""

    def __init__(self, key: str, what: str, where: SourceLocation) -> None:
        self.key, self.what, self.where = key, what, where

    def __enter__(self) -> None:
        session = _SESSION
        if session is not None and session.channel is not None:
            _send(session.channel, b'B', (self.key, self.what, tuple(self.where)))

    def __exit__(self, kind: Any, exc: Any, tb: Any) -> None:
        session = _SESSION
        if session is not None and session.channel is not None:
            _send(session.channel, b'E', self.key)


def running(key: str, what: str, where: SourceLocation) -> _Running:
    """A context manager around the code ``what`` while it runs: the child tells the parent,
    which blames it if the child dies or runs out of time meanwhile (reported at ``where``)."""
    return _Running(key, what, where)


def memory_problem(what: str) -> tuple[str, str]:
    """``(code, message)`` for code that ran out of the memory it may take."""
    limit = _SESSION.limits.memory_mib if _SESSION is not None else DEFAULT_MEMORY_MIB
    return ('NODL529', f'{what} needed more memory than --launch-memory {limit:g} MiB allows and '
            'was stopped (an allocation without end?); raise --launch-memory if it needs more')


def python_expression(expression: str, modules: list[str], where: SourceLocation) -> Any:
    """``$(eval EXPR [MODULES])``: the value of ``expression`` with ``modules`` imported (the
    names of :mod:`math` given as launch gives them), run as :func:`admit` allows (``where``:
    the file it is written in, to blame it if it stops the sandbox).

    Raises :class:`~nodl.launch.errors.LaunchProblem` (NODL510 for an error of the
    expression; NODL527-529 when it is not run) or an ``Unevaluable`` for ``--no-exec``."""
    import importlib
    import math

    from nodl.launch.errors import LaunchProblem, Unevaluable

    what = f'$(eval {expression!r})'
    refusal = admit('eval', f'eval\0{expression}\0{",".join(modules)}', what)
    if refusal is not None:
        if refusal.severity is Severity.WARNING:
            unknown = Unevaluable(refusal.message)
            unknown.code = refusal.code
            raise unknown
        raise LaunchProblem(refusal.code, refusal.message)
    with running(f'eval\0{expression}\0{",".join(modules)}', what, where):
        names: dict[str, Any] = {}
        for module_name in modules:
            try:
                module = math if module_name == 'math' else importlib.import_module(module_name)
            except MemoryError:
                raise LaunchProblem(*memory_problem(what)) from None
            except Exception as exc:  # ImportError, or what importing the module raised
                raise LaunchProblem('NODL510', f"$(eval): cannot import module '{module_name}': "
                                               f'{type(exc).__name__}: {exc}') from None
            if module.__name__ == 'math':
                names.update(vars(module))
            names[module.__name__] = module
        try:
            return eval(expression, {}, names)  # noqa: S307 - what launch itself does
        except MemoryError:
            raise LaunchProblem(*memory_problem(what)) from None
        except RecursionError:
            raise LaunchProblem('NODL510', f'$(eval) of {expression!r} failed: it recurses without '
                                           'end (RecursionError)') from None
        except Exception as exc:  # any error of the user's expression
            raise LaunchProblem('NODL510', f'$(eval) of {expression!r} failed: '
                                           f'{type(exc).__name__}: {exc}') from None
        except SystemExit as exc:  # exit() in the expression ends the launch, not the analysis
            raise LaunchProblem('NODL510', f'$(eval) of {expression!r} exits (SystemExit: '
                                           f'{exc.code!r})') from None


# -- the walk, in a child if it must ------------------------------------------------------

def contained(walk: Callable[[], LaunchResult], root: str, limits: LaunchLimits | None = None
              ) -> LaunchResult:
    """Run ``walk`` (a launch walk from the launch file ``root``) with its Python code kept
    to ``limits`` (see the module's documentation).  Never raises for the launch's code."""
    global _SESSION
    saved = _SESSION
    if saved is not None and saved.in_child:  # a launch read from a launch's code: as it is
        return walk()
    limits = limits or LaunchLimits()
    session = _SESSION = _Session(limits)
    try:
        try:
            return walk()
        except NeedsSandbox:
            pass
        deadline = time.monotonic() + limits.timeout
        failures: list[_Failure] = []
        result: LaunchResult | None = None
        for _ in range(MAX_ATTEMPTS):
            outcome = _run_child(walk, session, root, deadline)
            if not isinstance(outcome, _Failure):
                result, met = outcome
                session.met.update(met)
                break
            failures.append(outcome)
            if outcome.key:
                session.poisoned[outcome.key] = outcome.refusal
            if not outcome.key or time.monotonic() >= deadline:
                if outcome.refusal.code == 'NODL528' or time.monotonic() >= deadline:
                    session.spent = Refusal('NODL528', f'the Python code of this launch already took '
                                            f'the --launch-timeout of {limits.timeout:g} s')
                else:
                    reason = outcome.refusal.message
                    for suffix in (_missing('file'), _missing('eval')):
                        reason = reason.replace(suffix, '')
                    session.spent = Refusal(outcome.refusal.code, reason)
                break
        else:
            session.spent = Refusal('NODL527', f'{MAX_ATTEMPTS} pieces of Python code of this launch '
                                    'already failed; the rest is not run')
        if result is None:
            result = walk()  # here: every piece of code left is refused, none runs
        from nodl.diagnostics import Diagnostic

        for failure in failures:
            if failure.key not in session.met:  # not met again: said where it was running
                where = failure.where
                result.diagnostics.append(Diagnostic(
                    failure.refusal.severity, failure.refusal.message, (), where.file, where.line,
                    where.column, code=failure.refusal.code))
        return result
    finally:
        _SESSION = saved


def _send(channel: int, kind: bytes, payload: Any) -> None:
    data = pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL)
    view = memoryview(kind + len(data).to_bytes(8, 'big') + data)
    while view:
        written = os.write(channel, view)
        view = view[written:]


def _limit_child(limits: LaunchLimits, seconds: float) -> None:
    """In the child: no core dump, its address space and CPU time bounded."""
    import resource

    def lower(which: int, soft: int) -> None:
        old_soft, hard = resource.getrlimit(which)
        for bound in (old_soft, hard):  # a limit already lower stays
            if bound != resource.RLIM_INFINITY:
                soft = min(soft, bound)
        resource.setrlimit(which, (soft, hard))

    lower(resource.RLIMIT_CORE, 0)
    try:
        with open('/proc/self/statm', 'rb') as stream:
            mapped = int(stream.read().split()[0]) * os.sysconf('SC_PAGE_SIZE')
    except (OSError, ValueError, IndexError):
        mapped = 0
    lower(resource.RLIMIT_AS, mapped + int(limits.memory_mib * _MIB))
    lower(resource.RLIMIT_CPU, int(seconds) + 2)


def _child(walk: Callable[[], LaunchResult], session: _Session, channel: int, seconds: float) -> None:
    """The forked child: walk, send the result, end (never returns into the caller)."""
    status = 0
    try:
        os.setpgid(0, 0)
        import faulthandler

        faulthandler.disable()  # a crash of the launch's code is reported, not dumped
        _limit_child(session.limits, seconds)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.close(null)
        session.in_child = True
        session.channel = channel
        result = walk()
        _send(channel, b'R', (result, sorted(session.met)))
    except BaseException as exc:  # noqa: B036 - whatever happens, the parent hears of it
        status = 70
        with contextlib.suppress(BaseException):  # the pipe is gone: the exit status says enough
            _send(channel, b'X', f'{type(exc).__name__}: {exc}'[:2000])
    finally:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(BaseException):  # a closed stream: nothing more to say
                stream.flush()
        os._exit(status)  # the forked child ends here: it never returns into the caller's code


class _Unpickler(pickle.Unpickler):
    """Only the launch model's own classes: what the child sends cannot run code here."""

    _ALLOWED = {
        ('nodl.launch.model', name) for name in (
            'LaunchResult', 'LaunchedNode', 'LaunchArgument', 'ParameterSource', 'SourceLocation',
            'LaunchRemap', 'RunTimeSource')} | {
        ('nodl.diagnostics', 'Diagnostic'), ('nodl.diagnostics', 'Severity'),
        ('nodl.location', 'Location'),  # (SourceLocation is nodl.location.Location)
        ('nodl.launch.params', 'RuntimeValue'),
        ('builtins', 'set'), ('builtins', 'frozenset'), ('builtins', 'complex')}

    def find_class(self, module: str, name: str) -> Any:
        if (module, name) not in self._ALLOWED:
            raise pickle.UnpicklingError(f'{module}.{name} is not part of a launch result')
        return super().find_class(module, name)


def _loads(data: bytes) -> Any:
    return _Unpickler(io.BytesIO(data)).load()


def _signal_text(number: int) -> str:
    try:
        name = signal.Signals(number).name
    except ValueError:
        name = f'signal {number}'
    why = {
        'SIGSEGV': ' (a segmentation fault: a fault in native code such as ctypes, or a C stack '
                   'overflow from recursion too deep)',
        'SIGBUS': ' (a bus error in native code)', 'SIGABRT': ' (an abort, as by os.abort())',
        'SIGFPE': ' (an arithmetic fault in native code)', 'SIGILL': ' (an illegal instruction)',
    }.get(name, '')
    return f'it was killed by {name}{why}'


def _run_child(walk: Callable[[], LaunchResult], session: _Session, root: str,
               deadline: float) -> tuple[LaunchResult, list[str]] | _Failure:
    """One child: its result and the keys of refused code it met, or what went wrong."""
    import select

    for stream in (sys.stdout, sys.stderr):  # what is buffered is written once, not twice
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
    seconds = max(deadline - time.monotonic(), 0.0)
    read_end, write_end = os.pipe()
    # What the child inherits is moved out of the collector's generations while it forks: the
    # child's collections then do not walk it (nor copy the pages it is on); the parent's
    # objects go back at once (a program that keeps objects frozen itself is left alone).
    moved = gc.get_freeze_count() == 0
    if moved:
        gc.freeze()
    pid = os.fork()
    if pid != 0 and moved:
        gc.unfreeze()
    if pid == 0:
        os.close(read_end)
        _child(walk, session, write_end, seconds)
    os.close(write_end)
    buffer = bytearray()
    opened: list[tuple[str, str, SourceLocation]] = []
    answer: Any = None
    problem = ''
    status: int | None = None
    try:
        while answer is None and not problem:
            left = deadline - time.monotonic()
            if left <= 0:
                problem = 'timeout'
                break
            ready, _, _ = select.select([read_end], [], [], min(left, 0.05))
            if ready:
                chunk = os.read(read_end, 1 << 20)
                if not chunk:  # every writer gone: the child is ending
                    status = _wait(pid, deadline)
                    problem = 'timeout' if status is None else 'ended'
                    break
                buffer += chunk
                while len(buffer) >= 9 and answer is None and not problem:
                    size = int.from_bytes(buffer[1:9], 'big')
                    if size > MAX_RESULT_BYTES:
                        problem = 'too big'
                        break
                    if len(buffer) < 9 + size:
                        break
                    kind, data = bytes(buffer[:1]), bytes(buffer[9:9 + size])
                    del buffer[:9 + size]
                    try:
                        payload = _loads(data)
                    except Exception:  # noqa: BLE001 - garbage on the pipe: the child is not trusted
                        problem = 'garbage'
                        break
                    if kind == b'B' and isinstance(payload, tuple) and len(payload) == 3:
                        opened.append((str(payload[0]), str(payload[1]), SourceLocation(*payload[2])))
                    elif kind == b'E':
                        for index in range(len(opened) - 1, -1, -1):
                            if opened[index][0] == payload:
                                del opened[index:]
                                break
                    elif kind == b'R':
                        answer = payload
                    elif kind == b'X':
                        problem = f'error: {payload}'
                    else:
                        problem = 'garbage'
            elif status is None:
                status = _peek(pid)
                if status is not None:  # ended, its pipe held open by a process it started
                    problem = 'ended'
    finally:
        if status is None:
            status = _peek(pid)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(pid, signal.SIGKILL)  # the child and whatever it started
        os.waitpid(pid, 0)
        os.close(read_end)
    if answer is not None and isinstance(answer, tuple) and len(answer) == 2:
        from nodl.launch.model import LaunchResult

        result, met = answer
        if isinstance(result, LaunchResult):
            return result, [str(key) for key in met]
        problem = 'garbage'
    key, what, where = opened[-1] if opened else ('', 'the evaluation of this launch',
                                                 SourceLocation(root, 1, 1))
    return _Failure(key, what, where, _blame(what, problem, status, session.limits))


def _blame(what: str, problem: str, status: int | None, limits: LaunchLimits) -> Refusal:
    """The refusal for code that made the child fail (``status``: its wait status, if ended)."""
    missing = '; the nodes it would start are missing from the analysis'
    if what.startswith('$(eval'):
        missing = _missing('eval')
    signalled = status is not None and os.WIFSIGNALED(status)
    number = os.WTERMSIG(status) if status is not None and signalled else 0
    if problem == 'timeout' or number == signal.SIGXCPU:
        return Refusal('NODL528', f'{what} did not finish within --launch-timeout '
                       f'{limits.timeout:g} s and was stopped (an endless loop, or a wait for '
                       f'something that never comes){missing}; raise --launch-timeout if it needs '
                       'longer')
    if problem == 'too big':
        return Refusal('NODL529', f'{what} gave a result larger than {MAX_RESULT_BYTES // _MIB} MiB; '
                       f'it is not read{missing}')
    if number == signal.SIGKILL:
        return Refusal('NODL529', f'{what} was killed by SIGKILL while it ran, as the system does '
                       f'when memory runs out{missing}; lower what it allocates, or raise '
                       '--launch-memory if the system has the memory')
    if signalled:
        return Refusal('NODL527', f'{what} crashed the process that ran it: {_signal_text(number)}'
                       f'{missing}')
    if problem.startswith('error: '):
        text = problem[len('error: '):]
        if text.startswith('MemoryError'):
            return Refusal('NODL529', memory_problem(what)[1] + missing)
        return Refusal('NODL527', f'{what} stopped the process that ran it ({text}){missing}')
    if problem == 'garbage':
        return Refusal('NODL527', f'{what} wrote over the channel the analyser reads its result '
                       f'from; the result is not read{missing}')
    code = os.WEXITSTATUS(status) if status is not None and os.WIFEXITED(status) else -1
    return Refusal('NODL527', f'{what} ended the process that ran it (exit status {code}: '
                   f'os._exit() or an exit in native code) before the launch was read{missing}')


def _peek(pid: int) -> int | None:
    """The child's wait status if it has ended, without reaping it (its process group stays
    ours to kill)."""
    try:
        info = os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT)
    except ChildProcessError:
        return None
    if info is None:
        return None
    if info.si_code == os.CLD_EXITED:
        return (info.si_status & 0xFF) << 8
    return info.si_status & 0x7F  # killed or dumped: the signal


def _wait(pid: int, deadline: float) -> int | None:
    """The child's wait status once it ends (not reaped), or None at the deadline."""
    while True:
        status = _peek(pid)
        if status is not None or time.monotonic() >= deadline:
            return status
        time.sleep(0.005)
