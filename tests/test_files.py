"""Finding NoDL files (nodl.files)."""

from __future__ import annotations

import os

from conftest import FIXTURES
from nodl.files import STDIN, Target, find_nodl_files

TREE = FIXTURES / 'tree'


def test_directories_are_searched_recursively_for_the_three_suffixes() -> None:
    targets = find_nodl_files([str(TREE)])
    assert [os.path.relpath(t.path, TREE) for t in targets if t.problem is None] == [
        'a.nodl.yaml', os.path.join('sub', 'b.nodl.json'), os.path.join('sub', 'c.nodl.yml')]


def test_explicit_files_are_taken_whatever_their_extension() -> None:
    path = str(TREE / 'sub' / 'ignored.yaml')
    assert find_nodl_files([path]) == [Target(path)]


def test_stdin_and_problems_keep_their_order() -> None:
    empty = str(TREE / 'empty_dir')
    targets = find_nodl_files(['-', 'missing.yaml', empty])
    assert targets[0] == Target(STDIN)
    assert targets[1] == Target('missing.yaml', 'no such file or directory')
    assert targets[2].path == empty and 'no NoDL files' in (targets[2].problem or '')


# -- scanning directories like colcon (issue 8, section 3) ------------------------------------

SCAN = FIXTURES / 'scan'


def _workspace(tmp_path) -> str:
    """A colcon-like tree built from the scan fixtures (links and pipes cannot be checked in)."""
    import shutil

    src = tmp_path / 'ws' / 'src' / 'pkg'
    src.mkdir(parents=True)
    shutil.copy(SCAN / 'valid.nodl.yaml', src / 'a.nodl.yaml')
    return str(tmp_path / 'ws')


def _found(root: str) -> list[str]:
    return [os.path.relpath(t.path, root) for t in find_nodl_files([root])
            if t.problem is None and t.skipped is None]


def test_a_named_pipe_in_a_directory_is_skipped_with_a_note_not_opened(tmp_path) -> None:
    ws = _workspace(tmp_path)
    os.mkfifo(os.path.join(ws, 'src', 'pkg', 'pipe.nodl.yaml'))
    targets = find_nodl_files([ws])  # would block forever if the pipe were opened
    pipe = [t for t in targets if t.path.endswith('pipe.nodl.yaml')]
    assert len(pipe) == 1 and pipe[0].problem is None and 'named pipe' in (pipe[0].skipped or '')
    assert _found(ws) == [os.path.join('src', 'pkg', 'a.nodl.yaml')]


def test_an_explicit_named_pipe_is_a_target_marked_special(tmp_path) -> None:
    pipe = str(tmp_path / 'p.yaml')
    os.mkfifo(pipe)
    assert find_nodl_files([pipe]) == [Target(pipe, None, 'named pipe')]


def test_symlinked_directories_are_followed_once_without_looping(tmp_path) -> None:
    import shutil

    ws = _workspace(tmp_path)
    repo = tmp_path / 'repo' / 'linked_pkg'
    repo.mkdir(parents=True)
    shutil.copy(SCAN / 'valid.nodl.yaml', repo / 'b.nodl.yaml')
    os.symlink(repo, os.path.join(ws, 'src', 'linked_pkg'))          # a repository linked into src/
    os.symlink('..', repo / 'up')                                      # a loop back to an ancestor
    os.symlink(os.path.join(ws, 'src'), os.path.join(ws, 'src', 'pkg', 'again'))  # a loop in the tree
    assert sorted(_found(ws)) == [os.path.join('src', 'linked_pkg', 'b.nodl.yaml'),
                                  os.path.join('src', 'pkg', 'a.nodl.yaml')]


def test_ignore_markers_hidden_and_colcon_output_directories_are_skipped(tmp_path) -> None:
    import shutil

    ws = _workspace(tmp_path)
    for skipped in ('build/pkg', 'install/pkg/share', 'log/latest', '.git/x', 'src/ignored',
                    'src/ament_ignored'):
        folder = os.path.join(ws, skipped)
        os.makedirs(folder)
        shutil.copy(SCAN / 'valid.nodl.yaml', os.path.join(folder, 'copy.nodl.yaml'))
    open(os.path.join(ws, 'src', 'ignored', 'COLCON_IGNORE'), 'w').close()
    open(os.path.join(ws, 'src', 'ament_ignored', 'AMENT_IGNORE'), 'w').close()
    assert _found(ws) == [os.path.join('src', 'pkg', 'a.nodl.yaml')]
    # named on the command line, a directory is scanned whatever it holds
    assert _found(os.path.join(ws, 'install')) == [os.path.join('pkg', 'share', 'copy.nodl.yaml')]


def test_a_dangling_link_named_like_a_nodl_file_is_reported(tmp_path) -> None:
    ws = _workspace(tmp_path)
    link = os.path.join(ws, 'src', 'pkg', 'gone.nodl.yaml')
    os.symlink(os.path.join(ws, 'nowhere.yaml'), link)
    problems = [t for t in find_nodl_files([ws]) if t.problem]
    assert problems == [Target(link, 'a symbolic link to a file or directory that does not exist')]


def test_tidy_path_takes_out_dot_steps_and_keeps_relative_paths_relative(tmp_path) -> None:
    from nodl.files import tidy_path

    (tmp_path / 'launch').mkdir()
    (tmp_path / 'config').mkdir()
    (tmp_path / 'config' / 'x.yaml').write_text('{}')
    assert tidy_path(str(tmp_path / 'launch' / '..' / 'config' / '.' / 'x.yaml')) == \
        str(tmp_path / 'config' / 'x.yaml')
    assert tidy_path('launch/../config//x.yaml') == os.path.join('config', 'x.yaml')
    assert tidy_path('./x.yaml') == 'x.yaml'
    assert tidy_path('') == ''
    assert tidy_path(str(tmp_path / 'gone' / '..' / 'none.yaml')) == str(tmp_path / 'none.yaml')


def test_tidy_path_keeps_a_dot_dot_that_a_symbolic_link_makes_lead_elsewhere(tmp_path) -> None:
    from nodl.files import tidy_path

    (tmp_path / 'real' / 'deep').mkdir(parents=True)
    (tmp_path / 'real' / 'x.yaml').write_text('{}')      # what link/../x.yaml opens
    (tmp_path / 'link').symlink_to(tmp_path / 'real' / 'deep')
    through_link = str(tmp_path / 'link' / '..' / 'x.yaml')
    assert os.path.isfile(through_link) and not os.path.exists(tmp_path / 'x.yaml')
    assert tidy_path(through_link) == through_link
    (tmp_path / 'x.yaml').write_text('{}')                # a different file of the same name
    assert tidy_path(through_link) == through_link


def test_an_os_error_is_said_in_words_without_errno() -> None:
    import errno

    from nodl.files import describe_os_error

    assert describe_os_error(FileNotFoundError(errno.ENOENT, 'No such file or directory', 'x')) \
        == 'No such file or directory'  # the system's words, without '[Errno 2]' and the path
    assert describe_os_error(IsADirectoryError()) == 'is a directory, not a file'  # no strerror
    assert describe_os_error(OSError(errno.ENOSPC, 'No space left on device')) == 'No space left on device'
    assert describe_os_error(OSError(errno.EIO, None)) == 'Input/output error'  # words from the errno
    assert describe_os_error(OSError('the file is locked')) == 'the file is locked'  # no errno


UNREADABLE = FIXTURES / 'files' / 'unreadable'


def test_no_raw_errno_text_reaches_the_user() -> None:
    """Real failure paths of the verbs (a missing file, a directory where a file is wanted,
    an include and a parameter file that cannot be read, a mixin that is a directory, an
    output into a folder that does not exist) never print '[Errno N]'."""
    import subprocess
    import sys

    from conftest import REPO

    missing = str(UNREADABLE / 'no_such.nodl.yaml')
    folder = str(UNREADABLE / 'a_directory.yaml')
    node = str(FIXTURES / 'analysis' / 'prefix' / 'share' / 'nav' / 'nodl' / 'planner.nodl.yaml')
    runs = [
        ['validate', missing], ['validate', folder], ['show', missing], ['show', folder],
        ['show', str(UNREADABLE / 'mixin_dir.nodl.yaml')], ['deps', missing], ['deps', folder],
        ['export', missing], ['params', missing], ['params', folder],
        ['params', 'check', missing, '--definition', node], ['params', 'check', folder, '--definition', node],
        ['analyse', missing], ['analyse', folder], ['analyse', str(UNREADABLE / 'bad_refs.launch.xml')],
        ['analyse', str(UNREADABLE / 'bad_refs.launch.xml'), '--format', 'json'],
        # an output under a file (a folder cannot be made there)
        ['policy', missing], ['policy', node, '-o', str(UNREADABLE / 'bad_refs.launch.xml' / 'p.xml')],
        ['convert', missing, '-o', str(UNREADABLE / 'bad_refs.launch.xml' / 'out')],
        ['generate', node, '--language', 'python', '-o',
         str(UNREADABLE / 'bad_refs.launch.xml' / 'n.py')],
    ]
    for args in runs:
        done = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                              capture_output=True, timeout=60)
        said = done.stdout + done.stderr
        assert done.returncode != 0, (args, said)
        assert '[Errno' not in said and 'Traceback' not in said, (args, said)
