"""``python -m jointlin …`` and the ``jointlin`` command of the installed package: the
harness's command line, run by the extension module exactly as the ``jointlin`` program
runs it (same arguments, outputs, messages and exit codes)."""

import signal
import sys

from . import _native


def main() -> None:
    """Runs the command line of this process and exits with its code."""
    # The command installs its own SIGINT/SIGTERM notice once its outputs are opened;
    # before that, Ctrl-C ends it at once, as it ends the program.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    sys.exit(_native.cli(["jointlin", *sys.argv[1:]]))


if __name__ == "__main__":
    main()
