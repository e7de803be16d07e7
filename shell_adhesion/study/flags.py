"""Command-line values shared by the subcommands: a flag's number, an output file's path.
Each raises InputError with one line naming the flag, the value and the rule."""
from pathlib import Path

from shell_adhesion.errors import InputError

FIGURE_FORMATS = ("png", "pdf", "svg")


def number(flag, text, unit):
    """A flag's text as a float (finite or not: the rules say which values are fine)."""
    try:
        return float(text)
    except (TypeError, ValueError):
        raise InputError(f"{flag}: {text!r} must be a number ({unit})") from None


def check_output(flag, path, formats=None):
    """Refuse an output file whose folder does not exist, or (with `formats`) whose name
    does not end in one of them."""
    out = Path(path)
    if formats and out.suffix.lstrip(".").lower() not in formats:
        raise InputError(f"{flag}: {path}: the file name must end in "
                         f"{', '.join('.' + f for f in formats)}")
    if not out.parent.is_dir():
        raise InputError(f"{flag}: {path}: the folder {out.parent} does not exist")
