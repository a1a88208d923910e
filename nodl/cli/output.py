"""Where the command line writes: guarded streams, colour, a progress line.

Every verb writes through ``sys.stdout`` / ``sys.stderr`` as usual;
:func:`guarded_streams` swaps them for :class:`GuardedStream` objects while a
verb runs, so that:

* a failed write (``No space left on device``, an I/O error) becomes one
  :class:`OutputError` line and exit status 2, never "internal error";
* a closed pipe (``nodl validate . | head``) is a :class:`BrokenPipeError`
  that the runner turns into a quiet exit (status 141, as a tool killed by
  ``SIGPIPE`` has);
* on a terminal, severity words are coloured (unless ``NO_COLOR`` is set or
  ``--color never`` is given);
* a control character (but tab and newline) or a bidi control in what a verb
  writes is shown as an escape (``\\x1b``, ``\\u202e``), never obeyed.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING

from nodl.text_safety import visible

if TYPE_CHECKING:
    from typing import Any, TextIO

__all__ = ['OutputError', 'GuardedStream', 'guarded_streams', 'colour_enabled', 'colourize',
           'write_file', 'Progress', 'COLOR_CHOICES']

#: The values of ``--color``.
COLOR_CHOICES = ('auto', 'always', 'never')

#: ANSI colours of the severity words (bold red, bold magenta, bold cyan, as compilers print them).
_SEVERITY_COLOURS = {'error': '\033[1;31m', 'warning': '\033[1;35m', 'note': '\033[1;36m',
                     'info': '\033[1;36m'}
_RESET = '\033[0m'


class OutputError(Exception):
    """Output could not be written; the message is the one line the user sees."""


def colour_enabled(mode: str, stream: Any, environ: dict[str, str] | None = None) -> bool:
    """Whether to colour ``stream``: ``always``, ``never``, or ``auto`` (a terminal, and
    ``NO_COLOR`` unset or empty, as https://no-color.org asks)."""
    if mode == 'always':
        return True
    if mode == 'never':
        return False
    env = os.environ if environ is None else environ
    if env.get('NO_COLOR'):
        return False
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def colourize(text: str) -> str:
    """Colour the severity word of each ``WHERE: severity: message`` line of ``text``."""
    if ': ' not in text:
        return text
    lines = text.split('\n')
    for i, line in enumerate(lines):
        for word, colour in _SEVERITY_COLOURS.items():
            marker = f': {word}: '
            at = line.find(marker)
            if at < 0 and line.startswith(f'{word}: '):  # a line that starts with the word
                lines[i] = f'{colour}{word}{_RESET}: {line[len(word) + 2:]}'
                break
            if at >= 0:
                lines[i] = f'{line[:at]}: {colour}{word}{_RESET}: {line[at + len(marker):]}'
                break
    return '\n'.join(lines)


class GuardedStream:
    """A text stream whose write failures become :class:`OutputError` (see the module doc)."""

    def __init__(self, stream: TextIO, name: str, colour: bool = False) -> None:
        self._stream = stream
        self._name = name
        self.colour = colour
        #: Called before each write (the progress line clears itself there).
        self.before_write: Any = None

    def _failed(self, exc: OSError) -> OutputError:
        from nodl.files import describe_os_error

        return OutputError(f'cannot write {self._name}: {describe_os_error(exc)}')

    def write(self, text: str) -> int:
        if self.before_write is not None:
            self.before_write()
        # No control or bidi character a definition, a launch file or a running node gave
        # reaches the terminal or a log as it is: it could move the cursor, recolour or
        # reorder the text (nodl.text_safety); the colours are added after this.
        text = visible(text)
        if self.colour:
            text = colourize(text)
        try:
            return self._stream.write(text)
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise self._failed(exc) from None

    def writelines(self, lines: Any) -> None:
        for line in lines:
            self.write(line)

    def flush(self) -> None:
        try:
            self._stream.flush()
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise self._failed(exc) from None

    def __getattr__(self, name: str) -> Any:  # isatty, fileno, encoding, buffer, ...
        return getattr(self._stream, name)


class guarded_streams:
    """Context manager: ``sys.stdout`` and ``sys.stderr`` guarded (and coloured per ``mode``)."""

    def __init__(self, mode: str = 'auto') -> None:
        self.mode = mode

    def __enter__(self) -> tuple[GuardedStream, GuardedStream]:
        self._saved = (sys.stdout, sys.stderr)
        out = GuardedStream(sys.stdout, 'standard output', colour_enabled(self.mode, sys.stdout))
        err = GuardedStream(sys.stderr, 'standard error', colour_enabled(self.mode, sys.stderr))
        sys.stdout, sys.stderr = out, err
        return out, err

    def __exit__(self, *exc: object) -> None:
        sys.stdout, sys.stderr = self._saved


def write_file(path: str, text: str) -> None:
    """Write the report ``text`` to ``path`` (UTF-8) atomically (:func:`nodl.writing.write_file`:
    a report is always replaceable); a failure is a :class:`~nodl.writing.WriteError`,
    which the runner prints as one line (exit status 2), the previous file intact."""
    from nodl.writing import write_file as write_atomically

    write_atomically(path, text)


class Progress:
    """A one-line progress display on standard error, for long runs on a terminal.

    Nothing is shown unless standard error is a terminal and the run has
    lasted ``delay`` seconds; the line is redrawn at most every ``interval``
    seconds and is erased before anything else is written (to either stream).
    """

    def __init__(self, label: str, delay: float = 0.5, interval: float = 0.1,
                 stream: Any = None) -> None:
        import time

        self._clock = time.monotonic
        self._stream = stream if stream is not None else sys.stderr
        try:
            self.enabled = bool(self._stream.isatty())
        except (AttributeError, ValueError):
            self.enabled = False
        self._label = label
        self._start = self._clock()
        self._delay = delay
        self._interval = interval
        self._next = self._start + delay
        self._shown = False

    def update(self, done: int, total: int | None = None) -> None:
        """Show ``done`` (of ``total``), if it is time to."""
        if not self.enabled:
            return
        now = self._clock()
        if now < self._next:
            return
        self._next = now + self._interval
        text = f'{self._label}: {done}' + (f'/{total}' if total else '') + ' files checked'
        raw = getattr(self._stream, '_stream', self._stream)  # not through a guard's hook
        raw.write('\r\033[K' + text)
        raw.flush()
        self._shown = True

    def clear(self) -> None:
        """Erase the line (called before any other output)."""
        if self._shown:
            raw = getattr(self._stream, '_stream', self._stream)
            raw.write('\r\033[K')
            raw.flush()
            self._shown = False

