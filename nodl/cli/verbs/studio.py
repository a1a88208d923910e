"""``nodl studio``."""

from __future__ import annotations

import argparse
import sys

from nodl.cli.verb import EXIT_OK, EXIT_USAGE, Verb


class StudioVerb(Verb):
    """Compose a system in the browser: a local web application that edits a launch file.

    It edits through the composer (as nodl system does) and analyses on every change."""

    failure = None

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('launch_file', nargs='?', default='system.launch.xml',
                            metavar='LAUNCH_FILE',
                            help='the launch file to open (.launch.xml, .launch.yaml or '
                                 '.launch.py), created on Save when it does not exist '
                                 '(default: system.launch.xml here)')
        parser.add_argument('--port', type=_port, default=0, metavar='N',
                            help='the port on 127.0.0.1 to serve on (default: a free one)')
        parser.add_argument('--no-browser', action='store_true',
                            help='do not open a browser; only print the address')
        parser.add_argument('--no-exec', action='store_true',
                            help="never run the launch files' Python code (Python launch files, "
                                 '$(eval)), not even when asked on the page')
        from nodl.cli.arguments import add_definitions_argument

        add_definitions_argument(parser)
        parser.epilog = (
            'The studio listens on 127.0.0.1 only and prints its address, which carries a random '
            'token every request must give. It reads and writes files only under the launch '
            "file's folder and the --definitions folders. The launch files' Python code runs "
            'only when you click "Run launch Python" on the page (never with --no-exec). '
            'Stop it with Ctrl-C.')

    def main(self, args: argparse.Namespace) -> int:
        import os

        prog = 'nodl studio'
        from nodl.studio.vendor import INSTALL_HINT, missing_vendor_files

        missing = missing_vendor_files()
        if missing:
            print(f"{prog}: error: the studio's browser libraries are not installed "
                  f"({', '.join(missing)} missing from the nodl package): {INSTALL_HINT} "
                  '[NODL991]', file=sys.stderr)
            return EXIT_USAGE
        try:
            import starlette  # noqa: F401
            import uvicorn  # noqa: F401
        except ImportError as exc:
            print(f"{prog}: error: the studio needs {exc.name}: pip install "
                  "'nodl-toolkit[studio]' [NODL991]", file=sys.stderr)
            return EXIT_USAGE
        launch = os.path.abspath(args.launch_file)
        from nodl.studio.session import SUFFIXES

        if not launch.lower().endswith(SUFFIXES):
            print(f'{prog}: error: {args.launch_file}: a launch file name ends in '
                  f"{', '.join(SUFFIXES)}", file=sys.stderr)
            return EXIT_USAGE
        if os.path.isdir(launch) or not os.path.isdir(os.path.dirname(launch)):
            why = 'is a folder' if os.path.isdir(launch) else 'its folder does not exist'
            print(f'{prog}: error: {args.launch_file}: {why}', file=sys.stderr)
            return EXIT_USAGE
        from nodl.cli.arguments import load_definitions

        definitions = load_definitions(args, prog, start=os.path.dirname(launch))
        if isinstance(definitions, int):
            return definitions
        from nodl.studio.server import bind

        try:
            sock = bind(args.port)
        except OSError as exc:
            print(f'{prog}: error: cannot listen on 127.0.0.1:{args.port}: {exc.strerror or exc} '
                  '(give another --port, or 0 for a free one) [NODL992]', file=sys.stderr)
            return EXIT_USAGE
        from nodl.studio.guard import new_token
        from nodl.studio.session import Session, StudioError

        roots = [os.path.dirname(launch), *args.definitions]
        try:
            session = Session(launch, definitions=definitions, roots=roots,
                              execute=not args.no_exec, definition_folders=args.definitions)
        except StudioError as exc:
            sock.close()
            print(f'{prog}: error: {exc.message}', file=sys.stderr)
            return EXIT_USAGE
        from nodl.studio.app import create_app
        from nodl.studio.server import StudioServer

        token = new_token()
        port = int(sock.getsockname()[1])
        server = StudioServer(create_app(session, token, port), sock)
        address = f'http://127.0.0.1:{server.port}/?token={token}'
        print(f'nodl studio: {launch}', flush=True)
        print(f'nodl studio: open {address}', flush=True)
        print('nodl studio: stop it with Ctrl-C', flush=True)
        if not args.no_browser:
            import contextlib
            import webbrowser

            with contextlib.suppress(Exception):  # no browser: the address is printed
                webbrowser.open(address)
        server.run()
        print('nodl studio: stopped', flush=True)
        return EXIT_OK


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a port number") from None
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f'{value} is not a port number (0 to 65535)')
    return value


def copy_vendor_main(argv: list[str] | None = None) -> int:
    """``python -c 'from nodl.cli.verbs.studio import copy_vendor_main; copy_vendor_main()'
    NODE_MODULES``: copy the studio's browser libraries from npm's ``node_modules`` into the
    package (the Makefile's step after ``npm ci``); exit status 2 when one is missing."""
    from pathlib import Path

    from nodl.studio.vendor import copy_vendor

    args = sys.argv[1:] if argv is None else argv
    try:
        written = copy_vendor(Path(args[0]) if args else
                              Path(__file__).resolve().parents[2] / 'studio' / 'web' / 'node_modules')
    except OSError as exc:
        print(f'nodl studio: cannot copy its browser libraries: {exc}; run '
              '`npm ci --prefix nodl/studio/web` first', file=sys.stderr)
        return EXIT_USAGE
    for path in written:
        print(path)
    return EXIT_OK
