# SPDX-License-Identifier: GPL-3.0-or-later
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

Every output is written so that a failure never leaves a file that looks complete, as the C++
programs write theirs (shockgas::TextFile, sim/io/src/text_file.cpp):

    with atomic_output(args.json) as handle:        # a temporary file beside the target, renamed
        json.dump(table, handle)                     #  onto it when the block ends without an error
    with atomic_output_path(path) as name:          # the same for a writer that takes a file name
        with h5py.File(name, "w") as handle: ...

An error in the block (a full disk, an exception, Ctrl-C) removes the temporary file and leaves the
previous output, if any, whole. replaced_file(path) says which file is replaced: a symbolic link to
a regular file has its target replaced (the link stays a link); a device, a FIFO, /dev/stdout or any
link through /dev or /proc is written through in place.

Only the standard library: it loads wherever the package does (the source tree's python/, or the
installed module), but importing it still runs the package's __init__, which needs numpy and h5py.
"""
import argparse
import contextlib
import errno
import os
import stat
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
    made (permission, a read-only file system), for an existing file the directory of the file it
    replaces (replaced_file). Nothing is left behind. An existing path written through (/dev/stdout,
    a FIFO) is not opened here: its writing will tell."""
    if not path or path.endswith(os.sep):
        return "it names no file"
    if os.path.isdir(path):
        return "it is a directory"
    directory = os.path.dirname(path) or "."
    if not os.path.isdir(directory):
        return _missing_directory(directory)
    if os.path.exists(path):
        replaced = replaced_file(path)
        if replaced is None:  # written through: its writing will tell
            return None
        return _not_writable(replaced) or _probe(os.path.dirname(replaced) or ".")
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


# ---------------------------------------------------------------------------------------- writing
# A longer chain of symbolic links is taken for a loop and written through, where opening reports
# it: Linux's own limit (MAXSYMLINKS), and the C++ programs' (shockgas::replaced_file).
MAX_LINK_HOPS = 40
# The kernel's own names: a link through them (/dev/stdout -> /proc/self/fd/1 -> the file a shell
# opened for `>` or `>>`) is written through, since renaming onto that file would detach the
# redirection and lose what `>>` kept.
WRITTEN_THROUGH_TREES = ("/dev/", "/proc/")
# A temporary name is drawn at random (4 bytes); this many draws all taken means something else
# is wrong.
TEMPORARY_NAME_DRAWS = 100
# What open(path, "w") gives a new file before the umask takes its share; an existing file keeps
# its permission bits (never set-user-ID and the like, which a write by open() would drop).
NEW_FILE_MODE = 0o666
PERMISSION_BITS = 0o777


def replaced_file(path):
    """The regular file an output at `path` is written beside and renamed onto: path itself when it
    is new or a regular file, the end of a chain of symbolic links that ends at a regular file
    without passing through /dev or /proc; None when path is written through in place (a device
    such as /dev/null or /dev/full, a FIFO, /dev/stdout or any link through /dev or /proc, a link to
    nothing, a loop of links). The C++ programs' rule (shockgas::replaced_file)."""
    path = os.fspath(path)
    hop = path
    for hops in range(MAX_LINK_HOPS):
        try:
            mode = os.lstat(hop).st_mode
        except OSError:
            return path if hops == 0 else None  # new, or a link to nothing
        if stat.S_ISREG(mode):
            return hop
        if not stat.S_ISLNK(mode) or os.path.abspath(hop).startswith(WRITTEN_THROUGH_TREES):
            return None
        try:
            link = os.readlink(hop)
        except OSError:
            return None
        hop = os.path.join(os.path.dirname(hop), link)  # an absolute link stands alone
    return None


def _not_writable(existing):
    """Why the existing file may not be written (open() would refuse it: "Permission denied"), or
    None. Appends nothing: the file is unchanged."""
    try:
        open(existing, "ab").close()
    except OSError as error:
        return _cause(error)
    return None


def _naming(target, step, *arguments):
    """step(*arguments), an OSError of it naming `target`, the output the user asked for, rather than
    the temporary file."""
    try:
        return step(*arguments)
    except OSError as error:
        raise OSError(error.errno, error.strerror or str(error), target) from None


def _temporary_beside(replaced):
    """A new empty file beside `replaced`, with the permissions open(replaced, "w") would give: an
    existing file's bits, else NEW_FILE_MODE less the umask (the kernel applies it here as it does
    to open(); tempfile.mkstemp would give 0600)."""
    directory, name = os.path.split(replaced)
    for _ in range(TEMPORARY_NAME_DRAWS):
        temporary = os.path.join(directory, f".{name}.tmp.{os.getpid()}.{os.urandom(4).hex()}")
        try:
            descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, NEW_FILE_MODE)
        except FileExistsError:
            continue
        try:
            if os.path.exists(replaced):
                os.fchmod(descriptor, stat.S_IMODE(os.stat(replaced).st_mode) & PERMISSION_BITS)
        except BaseException:
            os.remove(temporary)
            raise
        finally:
            os.close(descriptor)
        return temporary
    raise FileExistsError(errno.EEXIST, f"no free temporary name in {TEMPORARY_NAME_DRAWS} draws", replaced)


def _sync(path, directory=False):
    """Forces a file's bytes (or a directory's entries, as far as the file system allows) to the disk."""
    try:
        descriptor = os.open(path, os.O_RDONLY | (os.O_DIRECTORY if directory else 0))
    except OSError:
        if directory:
            return
        raise
    try:
        os.fsync(descriptor)
    except OSError:
        if not directory:
            raise
    finally:
        os.close(descriptor)


@contextlib.contextmanager
def atomic_output_path(path, replace=True):
    """with atomic_output_path(path) as name: the block writes the file `name`, for a writer that takes
    a file name (h5py.File(name, "w"), ...). `name` is a new empty file beside the file `path`
    replaces (replaced_file), with the permissions open(path, "w") would give; when the block ends
    without an error it is synced and renamed onto that file in one step; on any exception
    (KeyboardInterrupt too) it is removed and the exception goes on, the previous file untouched.
    A path written through (a device, /dev/stdout) is given as it is. An existing file that may not
    be written is refused (PermissionError) as open() refuses it. Errors of these steps name `path`.

    replace=False: the output is put in place only if nothing took its name meanwhile
    (FileExistsError otherwise, the temporary file removed), never replacing a file."""
    target = os.fspath(path)
    replaced = replaced_file(target)
    if replaced is None:
        yield target
        return
    if os.path.exists(replaced):
        why = _not_writable(replaced)
        if why is not None:
            raise PermissionError(errno.EACCES, why, target)
    temporary = _naming(target, _temporary_beside, replaced)
    try:
        yield temporary
        _naming(target, _sync, temporary)
        if replace:
            _naming(target, os.replace, temporary, replaced)
        else:
            _naming(target, os.link, temporary, replaced)  # fails if the name was taken meanwhile
            os.remove(temporary)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(temporary)
        raise
    _sync(os.path.dirname(replaced) or ".", directory=True)


@contextlib.contextmanager
def atomic_output(path, mode="w", **open_arguments):
    """with atomic_output(path) as handle: open(path, mode) for the block, except that the file is
    written beside its destination and renamed onto it when the block ends (atomic_output_path):
    an error, a full disk or Ctrl-C leaves the previous file whole and no partial one. `mode` is
    "w", "wt" or "wb"; open_arguments are open()'s (encoding, newline, ...).

    A path written through that is this process's own standard output or error (/dev/stdout, or
    the file a shell redirected it to) is written through a duplicate of that descriptor, after the
    stream is flushed: it shares the shell's offset, so under `>` or `>>` the output lands after what
    the file held and what the script printed before, and before what it prints after, where "w"
    would truncate it (losing both). Any other path written through (/dev/fd/3 under `3>>`, a
    device, a FIFO) is opened to append, never truncated (the C++ TextFile does the same)."""
    if mode not in ("w", "wt", "wb"):
        raise ValueError(f"atomic_output: mode {mode!r}: an output is written whole ('w', 'wt' or 'wb')")
    target = os.fspath(path)
    with atomic_output_path(target) as name:
        if name == target:  # written through: no temporary file
            for stream in (sys.stdout, sys.stderr):
                if stream is not None:
                    stream.flush()
            descriptor = _standard_descriptor_at(name)
            if descriptor is not None:
                with os.fdopen(os.dup(descriptor), mode, **open_arguments) as handle:
                    yield handle
                return
            mode = mode.replace("w", "a")
        with open(name, mode, **open_arguments) as handle:  # closed (and flushed) before the rename
            yield handle


def _standard_descriptor_at(path):
    """1 or 2 when path is the file this process's standard output or error is open on, else None."""
    try:
        target = os.stat(path)
    except OSError:
        return None
    for descriptor in (1, 2):
        try:
            open_file = os.fstat(descriptor)
        except OSError:
            continue
        if (open_file.st_dev, open_file.st_ino) == (target.st_dev, target.st_ino):
            return descriptor
    return None
