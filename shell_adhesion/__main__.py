"""``python -m shell_adhesion``: the same as the ``shell-adhesion`` command."""
import sys

from shell_adhesion.cli import main

if __name__ == "__main__":
    sys.exit(main())
