"""nodl.writing: atomic writes, links, modes, the content marker, outputs that are inputs.

The data-loss tests write for real in a child process whose file size limit
(``RLIMIT_FSIZE``) is lower than the new content, with SIGXFSZ ignored so that
the write fails with EFBIG instead of killing the process.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import yaml

from conftest import FIXTURES, REPO
from nodl.writing import (
    WriteError,
    check_replaceable,
    holds_text,
    mark,
    marker_state,
    output_is_input,
    same_file,
    unmark,
    write_file,
    write_marked,
)

LIMITED = textwrap.dedent('''
    import resource, signal, sys
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
    sys.argv = ['nodl'] + sys.argv[1:]
    from nodl.cli.main import main
    sys.exit(main(sys.argv[1:]))
''')


def limited_nodl(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``nodl ARGS`` in a child that may not write a file larger than 4 KiB."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.run([sys.executable, '-c', LIMITED, *args], cwd=cwd, env=env, text=True,
                          capture_output=True, timeout=60)


def nodl(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=cwd, env=env, text=True,
                          capture_output=True, timeout=60)


# -- atomic writes ---------------------------------------------------------------------------


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path: Path) -> None:
    target = tmp_path / 'report.json'
    target.write_text('old\n', encoding='utf-8')
    code = textwrap.dedent(f'''
        import resource, signal, sys
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
        from nodl.writing import WriteError, write_file
        try:
            write_file({str(target)!r}, 'x' * 100000)
        except WriteError as exc:
            print(exc.diagnostic.code, exc)
    ''')
    run = subprocess.run([sys.executable, '-c', code], env=dict(os.environ, PYTHONPATH=str(REPO)),
                         text=True, capture_output=True, timeout=60)
    assert run.stdout == (f'NODL030 {target}: error: cannot write the file: File too large (the '
                          'file size limit); the previous file is unchanged [NODL030]\n'), run.stderr
    assert target.read_text(encoding='utf-8') == 'old\n'
    assert sorted(p.name for p in tmp_path.iterdir()) == ['report.json']


def test_a_verb_that_cannot_write_its_report_says_so_in_one_line(tmp_path: Path) -> None:
    launch = FIXTURES.parent.parent / 'examples' / 'system' / 'launch' / 'rover.launch.xml'
    log = tmp_path / 'analysis.log'
    log.write_text('the last run\n', encoding='utf-8')
    run = limited_nodl('analyse', str(launch), '--log', str(log), cwd=tmp_path)
    assert run.returncode == 2
    assert run.stderr.splitlines()[-1] == (f'{log}: error: cannot write the file: File too large '
                                           '(the file size limit); the previous file is unchanged '
                                           '[NODL030]')
    assert 'Traceback' not in run.stderr and '[Errno' not in run.stderr
    assert log.read_text(encoding='utf-8') == 'the last run\n'


def test_a_marked_file_that_cannot_be_rewritten_is_kept(tmp_path: Path) -> None:
    """Generated code over the limit: the previous generated file stays whole."""
    out = tmp_path / 'gen'
    definition = FIXTURES / 'generate' / 'everything.nodl.yaml'
    first = nodl('generate', str(definition), '--language', 'python', '-o', str(out),
                 '--class-name', 'Old')
    assert first.returncode == 0, first.stderr
    before = (out / 'everything_base.py').read_text(encoding='utf-8')
    assert len(before) > 4096
    run = limited_nodl('generate', str(definition), '--language', 'python', '-o', str(out),
                       cwd=tmp_path)
    assert run.returncode == 2 and 'Traceback' not in run.stderr
    assert f'{out / "everything_base.py"}: error: cannot write the file: File too large' in run.stderr
    assert (out / 'everything_base.py').read_text(encoding='utf-8') == before
    assert sorted(p.name for p in out.iterdir()) == ['everything_base.py']


def test_the_mode_of_a_replaced_file_is_kept(tmp_path: Path) -> None:
    target = tmp_path / 'run.sh'
    target.write_text('old\n')
    target.chmod(0o750)
    write_file(str(target), 'new\n')
    assert stat.S_IMODE(target.stat().st_mode) == 0o750 and target.read_text() == 'new\n'
    fresh = tmp_path / 'fresh.txt'
    mask = os.umask(0o027)
    try:
        write_file(str(fresh), 'x')
    finally:
        os.umask(mask)
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o640  # 0o666 less the umask, not mkstemp's 0o600
    write_file(str(fresh), 'x', mode=0o755)
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o755


def test_a_link_at_the_output_is_replaced_and_its_target_never_written(tmp_path: Path) -> None:
    victim = tmp_path / 'victim.txt'
    victim.write_text('precious\n')
    link = tmp_path / 'out' / 'report.txt'
    link.parent.mkdir()
    link.symlink_to(victim)
    write_file(str(link), 'report\n')
    assert victim.read_text() == 'precious\n'
    assert not link.is_symlink() and link.read_text() == 'report\n'
    dangling = tmp_path / 'out' / 'dangling.yaml'
    dangling.symlink_to(tmp_path / 'nowhere' / 'x.yaml')
    assert write_marked(str(dangling), 'a: 1\n')
    assert not dangling.is_symlink() and not (tmp_path / 'nowhere').exists()


def test_a_link_planted_where_a_verb_writes_is_not_followed(tmp_path: Path) -> None:
    victim = tmp_path / 'victim.yaml'
    victim.write_text('mine: true\n')
    out = tmp_path / 'gen'
    out.mkdir()
    (out / 'laser_driver_base.py').symlink_to(victim)
    run = nodl('generate', str(REPO / 'examples' / 'laser_driver.nodl.yaml'), '--language', 'python',
               '-o', str(out))
    assert run.returncode == 0, run.stderr
    assert victim.read_text() == 'mine: true\n'
    assert marker_state((out / 'laser_driver_base.py').read_text()) == 'valid'


def test_special_files_and_folders(tmp_path: Path) -> None:
    write_file(os.devnull, 'discarded\n')  # written in place, not renamed over
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)
    with pytest.raises(WriteError) as folder:
        write_file(str(tmp_path), 'x')
    assert folder.value.diagnostic.code == 'NODL034'
    with pytest.raises(WriteError) as missing:
        write_file(str(tmp_path / 'no' / 'such' / 'x.txt'), 'x')
    assert missing.value.diagnostic.code == 'NODL030'
    assert 'its folder does not exist; nothing was written' in missing.value.diagnostic.message
    write_file(str(tmp_path / 'made' / 'x.txt'), 'x', make_parents=True)
    assert (tmp_path / 'made' / 'x.txt').read_text() == 'x'


# -- the content marker ---------------------------------------------------------------------


def test_marker_lines_per_format() -> None:
    assert mark('a: 1\n', '#').splitlines()[0].startswith('# nodl: generated; sha256=')
    assert mark('int x;\n', '//').startswith('// nodl: generated; sha256=')
    xml = mark('<?xml version="1.0"?>\n<policy/>\n', 'xml').splitlines()
    assert xml[0] == '<?xml version="1.0"?>' and xml[1].startswith('<!-- nodl: generated; sha256=')
    assert xml[1].endswith(' -->')
    script = mark('#!/usr/bin/env python3\nprint(1)\n', '#').splitlines()
    assert script[0] == '#!/usr/bin/env python3' and script[1].startswith('# nodl: ')


def test_marker_states_and_hash() -> None:
    import hashlib

    text = mark('a: 1\n', '#')
    assert text.splitlines()[0] == '# nodl: generated; sha256=' + hashlib.sha256(b'a: 1\n').hexdigest()
    assert marker_state(text) == 'valid'
    assert marker_state(text.replace('a: 1', 'a: 2')) == 'edited'
    assert marker_state('a: 1\n') == 'absent'
    assert unmark(text) == 'a: 1\n' and mark(text, '#') == text  # re-marking replaces, not stacks
    assert marker_state('x\n' * 5 + text) == 'absent'  # only near the top


def test_marked_formats_still_load(tmp_path: Path) -> None:
    from nodl import load_node

    definition = (REPO / 'examples' / 'laser_driver.nodl.yaml').read_text(encoding='utf-8')
    marked = mark(definition, '#')
    assert marked.splitlines()[0].startswith('# yaml-language-server:')  # the modeline stays first
    assert load_node(marked).to_dict() == load_node(definition).to_dict()
    run = nodl('params', 'examples/laser_driver.nodl.yaml', '-o', str(tmp_path / 'p.yaml'))
    assert run.returncode == 0, run.stderr
    params = (tmp_path / 'p.yaml').read_text()
    assert marker_state(params) == 'valid' and yaml.safe_load(params) == yaml.safe_load(unmark(params))
    from rclpy.parameter import parameter_dict_from_yaml_file

    assert parameter_dict_from_yaml_file(str(tmp_path / 'p.yaml'), target_nodes=['/laser_driver'])


def test_check_replaceable(tmp_path: Path) -> None:
    target = tmp_path / 'x.yaml'
    assert check_replaceable(str(target)) is None  # nothing there
    target.write_text('mine: 1\n')
    refusal = check_replaceable(str(target))
    assert refusal is not None and refusal.code == 'NODL031' and refusal.file == str(target)
    assert check_replaceable(str(target), force=True) is None
    assert check_replaceable(str(target), mark('mine: 1\n', '#')) is None  # nothing would be lost
    target.write_text(mark('a: 1\n', '#'))
    assert check_replaceable(str(target), 'a: 2\n') is None
    target.write_text(mark('a: 1\n', '#') + 'b: 2\n')
    edited = check_replaceable(str(target), 'a: 3\n')
    assert edited is not None and edited.code == 'NODL032'
    target.write_bytes(b'\xff\xfe binary')
    assert check_replaceable(str(target), 'a: 1\n').code == 'NODL031'  # type: ignore[union-attr]


def test_write_marked_refuses_without_force_and_skips_identical(tmp_path: Path) -> None:
    target = tmp_path / 'x.nodl.json'  # JSON: no room for a marker
    assert write_marked(str(target), '{}\n') and target.read_text() == '{}\n'
    with pytest.raises(WriteError) as refused:
        write_marked(str(target), '{"a": 1}\n')
    assert refused.value.diagnostic.code == 'NODL031'
    assert write_marked(str(target), '{"a": 1}\n', force=True)
    yaml_file = tmp_path / 'x.yaml'
    assert write_marked(str(yaml_file), 'a: 1\n')
    before = yaml_file.stat().st_mtime_ns
    assert not write_marked(str(yaml_file), 'a: 1\n') and yaml_file.stat().st_mtime_ns == before


# -- outputs that are inputs ----------------------------------------------------------------


def test_same_file_through_links_and_hard_links(tmp_path: Path) -> None:
    original = tmp_path / 'a.yaml'
    original.write_text('a')
    (tmp_path / 'soft').symlink_to(original)
    os.link(original, tmp_path / 'hard')
    assert same_file(str(tmp_path / 'soft'), str(original))
    assert same_file(str(tmp_path / 'hard'), str(original))
    assert same_file(str(tmp_path / '.' / 'a.yaml'), str(original))
    assert not same_file(str(tmp_path / 'b.yaml'), str(original))
    clash = output_is_input(str(tmp_path / 'hard'), [str(original)], '--log')
    assert clash is not None and clash.code == 'NODL033' and clash.message.startswith('--log names')


@pytest.mark.parametrize('verb', [
    ['export', 'genparamlib', '{input}', '-o', '{output}'],
    ['params', '{input}', '-o', '{output}', '--force'],
    ['policy', '{input}', '-o', '{output}', '--force'],
    ['generate', '{input}', '--language', 'python', '-o', '{folder}', '--node-name', 'talker',
     '--force'],
])
def test_an_output_that_is_an_input_is_refused(tmp_path: Path, verb: list[str]) -> None:
    definition = tmp_path / 'talker.nodl.yaml'
    definition.write_bytes((FIXTURES / 'generate' / 'talker.nodl.yaml').read_bytes())
    original = definition.read_bytes()
    link = tmp_path / 'talker_base.py'  # generate's output name
    link.symlink_to(definition)
    output = str(link) if verb[0] == 'generate' else str(tmp_path / 'alias.yaml')
    if verb[0] != 'generate':
        os.link(definition, output)
    args = [a.format(input=str(definition), output=output, folder=str(tmp_path)) for a in verb]
    run = nodl(*args)
    assert run.returncode == 2, run.stdout + run.stderr
    assert run.stderr.splitlines()[-1].endswith(
        f'names an input of the command ({definition}): writing it would destroy the input; '
        'give another output path [NODL033]')
    assert definition.read_bytes() == original


def test_replacing_a_users_file_needs_force_in_every_verb(tmp_path: Path) -> None:
    definition = str(REPO / 'examples' / 'laser_driver.nodl.yaml')
    for verb in (['params', definition], ['policy', definition],
                 ['export', 'genparamlib', definition]):
        output = tmp_path / f'{verb[0]}.out.yaml'
        output.write_text('# my own file\n')
        refused = nodl(*verb, '-o', str(output))
        assert refused.returncode == 2, refused.stderr
        assert refused.stderr.splitlines()[-1] == (
            f'{output}: error: the file was not written by nodl (it has no nodl marker): not '
            'replaced; give another output path, or --force to replace it [NODL031]')
        assert output.read_text() == '# my own file\n'
        assert nodl(*verb, '-o', str(output), '--force').returncode == 0
        assert marker_state(output.read_text()) == 'valid'
        assert nodl(*verb, '-o', str(output)).returncode == 0  # nodl's own now: replaced freely


def test_analyse_and_check_never_write_over_what_they_read(tmp_path: Path) -> None:
    launch = tmp_path / 'rover.launch.xml'
    launch.write_bytes((REPO / 'examples' / 'system' / 'launch' / 'rover.launch.xml').read_bytes())
    (tmp_path / 'log').symlink_to(launch)
    for option in ('-o', '--log'):
        run = nodl('analyse', str(launch), option, str(tmp_path / 'log'))
        assert run.returncode == 2 and run.stderr.splitlines()[-1].endswith('[NODL033]'), run.stderr
    definition = tmp_path / 'talker.nodl.yaml'
    definition.write_bytes((FIXTURES / 'generate' / 'talker.nodl.yaml').read_bytes())
    run = nodl('check', '/talker', str(definition), '--junit', str(definition), '--timeout', '30')
    assert run.returncode == 2 and run.stderr.splitlines()[-1].startswith(f'{definition}: error: --junit names')
    assert launch.read_bytes() == (REPO / 'examples' / 'system' / 'launch' / 'rover.launch.xml').read_bytes()
    assert definition.read_bytes() == (FIXTURES / 'generate' / 'talker.nodl.yaml').read_bytes()


# -- every file a verb read is an input -----------------------------------------------------


def _system(tmp_path: Path) -> Path:
    """The example system with a definitions folder whose battery_monitor takes its
    diagnostics from a mixin next to it (a file the analysis reads only through the definition)."""
    import shutil

    root = tmp_path / 'system'
    shutil.copytree(REPO / 'examples' / 'system', root)
    defs = root / 'defs' / 'rover_base'
    defs.mkdir(parents=True)
    for name in ('battery_monitor', 'diagnostics'):
        shutil.copy(root / 'rover_base' / 'nodl' / f'{name}.nodl.yaml', defs)
    monitor = defs / 'battery_monitor.nodl.yaml'
    monitor.write_text(monitor.read_text().replace('nodl://rover_base/diagnostics',
                                                   'diagnostics.nodl.yaml'))
    return root


def _tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob('*')) if p.is_file()}


def test_analyse_refuses_to_write_any_file_the_analysis_read(tmp_path: Path) -> None:
    root = _system(tmp_path)
    (root / 'drawing.html').symlink_to(root / 'defs' / 'rover_base' / 'battery_monitor.nodl.yaml')
    before = _tree(root)
    launch = ['launch/rover.launch.xml', '--definitions', 'defs']
    for args, option, read in (
            (launch + ['-o', 'launch/sensors.launch.yaml'], '-o', 'launch/sensors.launch.yaml'),
            (launch + ['--log', 'launch/navigation.launch.py'], '--log', 'launch/navigation.launch.py'),
            (launch + ['-o', 'config/base.yaml'], '-o', 'config/base.yaml'),  # a node's parameters
            (launch + ['-o', 'nodl.toml'], '-o', 'nodl.toml'),  # the configuration
            (launch + ['--format', 'json', '-o', 'defs/rover_base/diagnostics.nodl.yaml'], '-o',
             'defs/rover_base/diagnostics.nodl.yaml'),  # a mixin of a definition found in defs
            (launch + ['--graph', 'drawing.html'], '--graph',
             'defs/rover_base/battery_monitor.nodl.yaml'),  # the definition, through a link
            (['defs/rover_base/battery_monitor.nodl.yaml', '-o',
              'defs/rover_base/diagnostics.nodl.yaml'], '-o', 'defs/rover_base/diagnostics.nodl.yaml')):
        run = nodl('analyse', *args, cwd=root)
        assert run.returncode == 2, (args, run.stderr)
        assert len(run.stderr.splitlines()) == 1, run.stderr
        assert run.stderr.startswith(f'{args[args.index(option) + 1]}: error: {option} names an '
                                     'input of the command ('), run.stderr
        assert os.path.samefile(root / read, root / run.stderr.split('(', 1)[1].split(')', 1)[0])
        assert run.stderr.rstrip().endswith('[NODL033]') and run.stdout == ''
    assert _tree(root) == before


def test_policy_refuses_to_write_any_file_it_read(tmp_path: Path) -> None:
    root = _system(tmp_path)
    (root / 'enclaves.yaml').write_text('/rover: ["/rover/**"]\n')
    before = _tree(root)
    launch = ['launch/rover.launch.xml', '--definitions', 'defs', '--allow-missing', '--force']
    for args, output in (
            (launch, 'launch/sensors.launch.yaml'), (launch, 'config/navigation.yaml'),
            (launch, 'defs/rover_base/diagnostics.nodl.yaml'), (launch, 'nodl.toml'),
            (['defs/rover_base/battery_monitor.nodl.yaml', '--force'],
             'defs/rover_base/diagnostics.nodl.yaml'),
            (['defs/rover_base/battery_monitor.nodl.yaml', '--enclave-map', 'enclaves.yaml'],
             'enclaves.yaml')):
        run = nodl('policy', *args, '-o', output, cwd=root)
        assert run.returncode == 2, (args, run.stderr)
        assert run.stderr.splitlines()[-1].startswith(f'{output}: error: -o names an input'), run.stderr
        assert run.stderr.rstrip().endswith('[NODL033]')
    assert _tree(root) == before


def test_params_export_generate_never_write_over_a_mixin(tmp_path: Path) -> None:
    root = _system(tmp_path)
    definition = 'defs/rover_base/battery_monitor.nodl.yaml'
    mixin = root / 'defs' / 'rover_base' / 'diagnostics.nodl.yaml'
    (root / 'battery_monitor_base.py').symlink_to(mixin)  # what generate writes
    os.link(mixin, root / 'alias.yaml')
    before = _tree(root)
    for verb in (['params', definition, '-o', 'alias.yaml', '--force'],
                 ['export', 'genparamlib', definition, '--with-mixins', '-o', 'alias.yaml', '--force'],
                 ['generate', definition, '--language', 'python', '-o', '.', '--force']):
        run = nodl(*verb, cwd=root)
        assert run.returncode == 2, (verb, run.stderr)
        last = run.stderr.splitlines()[-1]
        assert ' names an input of the command (' in last and last.endswith('[NODL033]'), last
        assert 'diagnostics.nodl.yaml' in last
    assert _tree(root) == before and (root / 'battery_monitor_base.py').is_symlink()


def test_new_never_writes_over_a_definition_it_read(tmp_path: Path) -> None:
    out = tmp_path / 'ws'
    definition = REPO / 'examples' / 'laser_driver.nodl.yaml'
    first = nodl('new', 'pkg', '--from', str(definition), '--build-type', 'ament_python', '-o', str(out))
    assert first.returncode == 0, first.stderr
    mine = out / 'pkg' / 'nodl' / 'laser_driver.nodl.yaml'
    mine.write_text(mine.read_text() + '# my change\n')  # the package's copy, now the source
    before = mine.read_bytes()
    for force in ([], ['--force']):
        run = nodl('new', 'pkg', '--from', str(mine), '--build-type', 'ament_python', '-o', str(out),
                   '--update', *force)
        assert run.returncode == 2, run.stderr
        lines = run.stderr.splitlines()  # (its mixin, copied beside it, comes first)
        mixin = mine.parent / 'diagnostics.nodl.yaml'
        assert lines == [f'{mixin}: error: -o names an input of the command ({mixin}): writing it '
                         'would destroy the input; give another output path [NODL033]'], lines
    assert mine.read_bytes() == before


def test_convert_never_writes_over_an_exported_legacy_file(tmp_path: Path) -> None:
    import shutil

    package = tmp_path / 'package'
    shutil.copytree(FIXTURES / 'legacy' / 'package', package)
    before = _tree(package)
    out = tmp_path / 'out'
    out.mkdir()
    first = nodl('convert', str(package / 'package.xml'), '-o', str(out))
    assert first.returncode == 0, first.stderr
    written = sorted(p.name for p in out.iterdir())
    for name in written:
        (out / name).unlink()
    exported = package / 'interfaces' / 'talker.nodl.xml'
    (out / written[0]).symlink_to(exported)  # a link where the converted file goes
    run = nodl('convert', str(package / 'package.xml'), '-o', str(out), '--force')
    assert run.returncode == 2, run.stderr
    assert f'names an input of the command ({exported})' in run.stdout + run.stderr
    assert _tree(package) == before


# -- no folder under -o leads outside it ----------------------------------------------------


def test_check_within(tmp_path: Path) -> None:
    from nodl.writing import check_within

    out, elsewhere = tmp_path / 'out', tmp_path / 'elsewhere'
    (out / 'real').mkdir(parents=True)
    elsewhere.mkdir()
    (out / 'planted').symlink_to(elsewhere)
    (out / 'inner').symlink_to(out / 'real')  # a link that stays inside is fine
    chosen = tmp_path / 'chosen'
    chosen.symlink_to(out)  # -o itself may be a link: the user chose it
    assert check_within(str(out / 'real' / 'x.py'), str(out)) is None
    assert check_within(str(out / 'inner' / 'x.py'), str(out)) is None
    assert check_within(str(out / 'new' / 'deeper' / 'x.py'), str(out)) is None
    assert check_within(str(chosen / 'real' / 'x.py'), str(chosen)) is None
    refused = check_within(str(out / 'planted' / 'sub' / 'x.py'), str(out))
    assert refused is not None and refused.code == 'NODL708'
    assert refused.file == str(out / 'planted' / 'sub' / 'x.py')
    assert refused.message == (f'not written: {out / "planted"} is a symbolic link to {elsewhere}, '
                               f'outside the output folder {out}; remove the link or give another '
                               'output folder')
    for outside in ('../x.py', 'a/../../x.py', 'inner/../../x.py'):
        assert check_within(str(out) + '/' + outside, str(out)).code == 'NODL708'  # type: ignore[union-attr]
    with pytest.raises(WriteError) as raised:
        write_file(str(out / 'planted' / 'sub' / 'x.py'), 'x', make_parents=True, within=str(out))
    assert raised.value.diagnostic.code == 'NODL708'
    with pytest.raises(WriteError):
        write_marked(str(out / 'planted' / 'x.yaml'), 'a: 1\n', within=str(out))
    assert list(elsewhere.iterdir()) == []


def test_a_planted_folder_link_redirects_no_verb(tmp_path: Path) -> None:
    elsewhere = tmp_path / 'elsewhere'
    elsewhere.mkdir()
    # nodl new: the package folder, or one inside it, planted as a link to a folder outside
    ws = tmp_path / 'ws'
    ws.mkdir()
    (ws / 'pkg').symlink_to(elsewhere)
    definition = str(REPO / 'examples' / 'laser_driver.nodl.yaml')
    run = nodl('new', 'pkg', '--from', definition, '--build-type', 'ament_python', '-o', str(ws), '--force')
    assert run.returncode == 2, run.stderr
    assert run.stderr.splitlines()[-1].endswith(
        f'not written: {ws / "pkg"} is a symbolic link to {elsewhere}, outside the output folder '
        f'{ws}; remove the link or give another output folder [NODL708]')
    (ws / 'pkg').unlink()
    (ws / 'pkg').mkdir()
    (ws / 'pkg' / 'test').symlink_to(elsewhere)
    run = nodl('new', 'pkg', '--from', definition, '--build-type', 'ament_python', '-o', str(ws), '--force')
    assert run.returncode == 2 and run.stderr.rstrip().endswith('[NODL708]'), run.stderr
    assert sorted(p.name for p in (ws / 'pkg').iterdir()) == ['test']  # refused before writing any
    # nodl extract -o DIR: the package's folder of the overlay
    out = tmp_path / 'drafts'
    out.mkdir()
    (out / 'demo_pkg').symlink_to(elsewhere)
    run = nodl('extract', str(REPO / 'tests' / 'fixtures' / 'extract' / 'python' / 'pkg'), '-o', str(out))
    assert run.returncode == 2
    assert f'not written: {out / "demo_pkg"} is a symbolic link to {elsewhere}' in run.stdout + run.stderr
    assert list(elsewhere.iterdir()) == []


def test_writing_loads_no_tempfile_and_makes_private_new_temporaries(tmp_path: Path) -> None:
    """nodl.writing makes its temporary files itself (tempfile would cost every command that
    may write ~4 ms of start-up): new (O_EXCL, never through a link), mode 0o600, beside the target."""
    from nodl.writing import _create_temporary

    done = subprocess.run([sys.executable, '-c', 'import sys, nodl.writing; print("tempfile" in sys.modules)'],
                          capture_output=True, text=True, timeout=60, cwd=REPO)
    assert done.stdout.strip() == 'False', done.stderr
    fd, first = _create_temporary(str(tmp_path), 'out.yaml')
    os.close(fd)
    fd, second = _create_temporary(str(tmp_path), 'out.yaml')
    os.close(fd)
    assert first != second and os.path.dirname(first) == str(tmp_path)
    assert os.path.basename(first).startswith('.out.yaml.') and first.endswith('.nodl-tmp')
    assert stat.S_IMODE(os.stat(first).st_mode) == 0o600


def test_holds_text_is_a_regular_file_with_exactly_that_text(tmp_path: Path) -> None:
    file = tmp_path / 'a.py'
    file.write_bytes('x = "\u00e9"\r\n'.encode())
    assert holds_text(str(file), 'x = "\u00e9"\r\n')
    assert not holds_text(str(file), 'x = "\u00e9"\n')  # newlines are kept as written
    assert not holds_text(str(file), 'x = "e"\r\n')
    assert not holds_text(str(tmp_path / 'missing.py'), '')
    assert not holds_text(str(tmp_path), '')
    (tmp_path / 'link.py').symlink_to(file)
    assert not holds_text(str(tmp_path / 'link.py'), 'x = "\u00e9"\r\n')  # a link is not followed
