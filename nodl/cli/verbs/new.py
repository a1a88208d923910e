"""``nodl new``."""

from __future__ import annotations

import argparse
import os
import sys

from nodl.cli.verb import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, Verb


class NewVerb(Verb):
    """Create a ROS 2 package (ament_python or ament_cmake) implementing node definitions."""

    failure = 'a definition is invalid'

    def add_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument('package', metavar='PACKAGE', help='the name of the new package')
        parser.add_argument('--from', dest='sources', action='append', nargs='+', required=True,
                            metavar='DEFINITION',
                            help='node definition files (one executable each, named after the '
                                 'file), or PACKAGE EXECUTABLE of a registered one; repeatable')
        parser.add_argument('--build-type', required=True, choices=('ament_python', 'ament_cmake'),
                            help='ament_python (rclpy nodes) or ament_cmake (rclcpp nodes)')
        parser.add_argument('-o', '--destination-directory', dest='output', default='.',
                            metavar='DIR', help='the package is created as DIR/PACKAGE (default: .)')
        parser.add_argument('--component', action='store_true',
                            help='ament_cmake: make each node an rclcpp component (a library '
                                 'registered with RCLCPP_COMPONENTS_REGISTER_NODE, and an '
                                 'executable that runs it alone)')
        parser.add_argument('--license', metavar='SPDX',
                            help='the license, as an SPDX id ament_copyright knows (Apache-2.0, '
                                 'BSD-2-Clause, BSD-3-Clause, BSL-1.0, GPL-3.0-or-later, '
                                 'LGPL-3.0-or-later, MIT, MIT-0): written into package.xml and a '
                                 'copyright header in every source file; needs --maintainer')
        parser.add_argument('--maintainer', nargs=2, metavar=('NAME', 'EMAIL'),
                            help="the maintainer in package.xml (and setup.py), and the copyright "
                                 "holder of the headers")
        parser.add_argument('--update', action='store_true',
                            help='the package exists: regenerate its generated files, add missing '
                                 'ones, keep every file of yours')
        parser.add_argument('--force', action='store_true',
                            help='replace every file, your own included')
        parser.epilog = (
            'Generated files (the definitions under nodl/ and, for ament_python, the '
            '<exe>_base.py modules) are rewritten by --update; every other file (your node '
            'implementations, package.xml, build files, parameter files, launch file, tests, '
            'README) is written once and kept. An ament_cmake package generates its C++ bases '
            'at build time (ament_nodl_generate_cpp).')

    def main(self, args: argparse.Namespace) -> int:
        from nodl.cli.report_options import show_diagnostics
        from nodl.scaffold import ScaffoldError, authorship, check_package_name, load_nodes, plan_package, write_package

        sources: list[list[str]] = []
        for group in args.sources:
            if len(group) == 2 and not os.path.isfile(group[0]):
                sources.append(group)  # PACKAGE EXECUTABLE
            else:
                sources.extend([item] for item in group)
        try:
            check_package_name(args.package)
            author = authorship(args.license, args.maintainer)
            nodes = load_nodes(sources, args.build_type)
            plan = plan_package(args.package, nodes, args.build_type, component=args.component,
                                author=author)
            report = write_package(plan, args.output, update=args.update, force=args.force)
        except ScaffoldError as exc:
            if exc.diagnostics:
                show_diagnostics(exc.diagnostics)
                print(f'nodl new: error: {exc}', file=sys.stderr)
                return EXIT_FAILURE
            print(f'nodl new: error: {exc}', file=sys.stderr)
            return EXIT_USAGE
        except OSError as exc:
            from nodl.files import describe_os_error

            print(f'nodl new: error: {exc.filename or args.output}: {describe_os_error(exc)}',
                  file=sys.stderr)
            return EXIT_USAGE
        for path in report.written:
            print(f'wrote {os.path.join(args.output, path)}')
        for path in report.kept:
            print(f'kept  {os.path.join(args.output, path)} (yours; --force replaces it)')
        return EXIT_OK
