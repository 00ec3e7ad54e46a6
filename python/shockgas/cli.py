"""How the project's Python scripts refuse a user's mistake: one line "<program>: error: <what>" on
stderr and exit status 2, as the C++ programs do (docs/cli-and-output.md), never argparse's usage
block or a traceback.

    from shockgas.cli import ArgumentParser, fail

    parser = ArgumentParser(description="...")    # argparse's, --help unchanged; a bad option, a
    args = parser.parse_args()                     # missing argument, a bad type or choice: one line
    ...
    fail(f"{path}: not a decay results file")      # one line, then SystemExit(2)

Only the standard library: it loads wherever the package does (the source tree's python/, or the
installed module), but importing it still runs the package's __init__, which needs numpy and h5py.
"""
import argparse
import os
import sys


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
