"""How the project's Python scripts refuse a user's mistake: one line "<program>: error: <what>" on
stderr and exit status 2, as the C++ programs do (docs/cli-and-output.md), never argparse's usage
block or a traceback.

    from shockgas.cli import ArgumentParser, fail

    parser = ArgumentParser(description="...")    # argparse's, --help unchanged; a bad option, a
    args = parser.parse_args()                     # missing argument, a bad type or choice: one line
    ...
    fail(f"{path}: not a decay results file")      # one line, then SystemExit(2)

An output path the script could not write is refused the same way, before the work rather than after
it (as the C++ programs' h5::check_writable does):

    check_output_file(args.json, "--json")         # "cannot write --json 'x/y.json': directory 'x'
    check_output_directory(args.out_dir, "--out-dir")  #  does not exist", "...: Permission denied"

output_file_problem(path) and output_directory_problem(path) give the cause alone (or None), for a
script that refuses through its own exception (sticky_pav.py); cannot_write(path, cause, option)
words the line, the cause a string or, for a failure only the writing finds (a full disk, a path
changed meanwhile), the OSError.

Only the standard library: it loads wherever the package does (the source tree's python/, or the
installed module), but importing it still runs the package's __init__, which needs numpy and h5py.
"""
import argparse
import os
import sys
import tempfile


def fail(message, program=None):
    """A user's mistake: prints "<program>: error: <message>" on one line to stderr (a message
    holding line breaks is joined with spaces) and exits with status 2. `program` defaults to the
    script's name, the last component of sys.argv[0], as argparse names it."""
    program = program or os.path.basename(sys.argv[0]) or "python"
    print(f"{program}: error: {' '.join(str(message).splitlines())}", file=sys.stderr)
    sys.exit(2)


class ArgumentParser(argparse.ArgumentParser):
    """argparse.ArgumentParser whose refusals (unknown option, missing argument, bad type or choice,
    and parser.error(...) called by the script) are one line "<prog>: error: <what>" and exit 2,
    without the usage block; --help prints what argparse prints. Subcommand parsers made with
    add_subparsers() are of this class too."""

    def error(self, message):
        fail(message, self.prog)


def cannot_write(path, cause, option=None):
    """The one line's text for an output that cannot be written: "cannot write <option> '<path>':
    <cause>", the cause a str or an OSError (its strerror: "Permission denied", "No space left on
    device", ...)."""
    if isinstance(cause, OSError):
        cause = _cause(cause)
    return f"cannot write {option + ' ' if option else ''}'{path}': {cause}"


def _cause(error):
    return error.strerror or str(error)


def _probe(directory):
    """Whether a file can be made in the existing `directory`: None, or the cause. A file is made and
    removed (os.access would say yes to root in a read-only directory, and not say why it says no)."""
    try:
        handle, name = tempfile.mkstemp(dir=directory, prefix=".shockgas-write-check-")
    except OSError as error:
        return _cause(error)
    os.close(handle)
    os.remove(name)
    return None


def _missing_directory(directory):
    """The cause when `directory`, the folder an output goes in, is not an existing directory."""
    existing = directory
    while not os.path.lexists(existing):  # the nearest that exists ("." and "/" do)
        existing = os.path.dirname(existing) or "."
    if not os.path.isdir(existing):
        return f"'{existing}' is not a directory"
    return f"directory '{directory}' does not exist"


def output_file_problem(path):
    """Why the output file `path` cannot be written, or None: its directory missing (or a file), the
    path a directory, an existing file that may not be written, a directory where no file may be
    made (permission, a read-only file system). Nothing is left behind. An existing path that is not
    a regular file (/dev/stdout, a FIFO) is not opened here: its writing will tell."""
    if not path or path.endswith(os.sep):
        return "it names no file"
    if os.path.isdir(path):
        return "it is a directory"
    directory = os.path.dirname(path) or "."
    if not os.path.isdir(directory):
        return _missing_directory(directory)
    if os.path.exists(path):
        if not os.path.isfile(path):
            return None
        try:
            open(path, "ab").close()  # appends nothing: the file is unchanged
        except OSError as error:
            return _cause(error)
        return None
    return _probe(directory)


def output_directory_problem(path):
    """Why `path` cannot serve as an output directory (made if missing), or None: a file in its
    place or in the way, or no file may be made in it, or it may not be made where it would go."""
    if not path:
        return "it names no directory"
    if os.path.exists(path):
        if not os.path.isdir(path):
            return "it exists and is not a directory"
        return _probe(path)
    parent = os.path.dirname(os.path.normpath(path)) or "."
    while not os.path.exists(parent):  # the nearest folder that exists ("." and "/" do)
        parent = os.path.dirname(parent) or "."
    if not os.path.isdir(parent):
        return f"'{parent}' is not a directory"
    why = _probe(parent)
    return None if why is None else f"it cannot be made in '{parent}': {why}"


def check_output_file(path, option=None, program=None):
    """Refuses (fail) an output file that cannot be written (output_file_problem)."""
    why = output_file_problem(path)
    if why is not None:
        fail(cannot_write(path, why, option), program)


def check_output_directory(path, option=None, program=None):
    """Refuses (fail) an output directory that cannot be made or written in (output_directory_problem)."""
    why = output_directory_problem(path)
    if why is not None:
        fail(cannot_write(path, why, option), program)
