"""What the commands share on their command lines: the parser whose errors are one line and exit
2, numbers checked against their range, and the warning of a cube whose campaign has not run every
cell."""
import argparse
import math
import sys

from .errors import InputError
from .files import OutputError


class OneLineParser(argparse.ArgumentParser):
    """A bad command line is bad input like any other: one line naming the problem, exit 2. The
    notes of old spellings (add_old_spelling) print once the whole line has parsed, so a line with
    an error prints the error alone."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (--help for the options)\n")

    def parse_args(self, args=None, namespace=None):
        parsed = super().parse_args(args, namespace)
        for note in vars(parsed).pop("old_spelling_notes", []):
            sys.stderr.write(f"rigid: note: {note}\n")
        return parsed


class _OldSpelling(argparse.Action):
    def __init__(self, option_strings, dest, current, **kwargs):
        self.current = current
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        if getattr(namespace, self.dest) is not None:
            parser.error(f"{option_string} is the old spelling of {self.current}; give only {self.current}")
        setattr(namespace, self.dest, values)
        notes = getattr(namespace, "old_spelling_notes", [])
        notes.append(f"{option_string} is now {self.current}; the old spelling goes in the next release")
        setattr(namespace, "old_spelling_notes", notes)


def add_old_spelling(parser, old, current, **kwargs):
    """Accepts `old` for one release as the old spelling of the option `current` (added before it,
    default None): hidden from --help, same value, one note on stderr (the C++ commands' rule,
    src/app/old_spellings.hpp). kwargs: the current option's type."""
    dest = next(a.dest for a in parser._actions if current in a.option_strings)
    parser.add_argument(old, dest=dest, action=_OldSpelling, current=current, help=argparse.SUPPRESS,
                        default=argparse.SUPPRESS, **kwargs)




def exit_status(command, run, args):
    """run() as a command does: its status; bad input (InputError, OutputError, an OSError) one line
    `COMMAND: error: ...` and 2; anything else is a bug of ours, one line and 1. A cube that cannot
    be fitted may be one whose campaign has not run the cells yet (`args.incomplete`): said too."""
    try:
        return run()
    except (InputError, OutputError) as e:
        incomplete = getattr(args, "incomplete", None)
        more = f" ({incomplete})" if incomplete and incomplete not in str(e) else ""
        sys.stderr.write(f"{command}: error: {e}{more}\n")
        return 2
    except OSError as e:
        sys.stderr.write(f"{command}: error: {e}\n")
        return 2
    except Exception as e:
        sys.stderr.write(f"{command}: internal error: {type(e).__name__}: {e}\n")
        return 1


def number_in(text, option, low=None, high=None):
    try:
        v = float(text)
    except ValueError:
        raise InputError(f"{option} {text!r}: expected a number")
    if not math.isfinite(v) or (low is not None and v < low) or (high is not None and v > high):
        raise InputError(f"{option} {text!r}: must be in [{low}, {high}]")
    return v


def check_completeness(cube, state, args):
    """A cube whose campaign has not run every cell: refused with --require-complete, else its
    warning kept for warn_incomplete (printed once the fit stands, so bad input stays one line)."""
    problem = cube.incomplete(state)
    if problem is not None and args.require_complete:
        raise InputError(problem + " (--require-complete)")
    args.incomplete = problem


def warn_incomplete(args):
    if getattr(args, "incomplete", None):
        sys.stderr.write(f"rigid {args.command}: warning: {args.incomplete}; the fits use the cells run so far\n")
