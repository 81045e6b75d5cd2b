"""The yfdem binary a script suite (tests/<name>/run) runs, checked before the suite starts.

YFDEM=path (relative to the repository's root, default ./yfdem), as `make check` passes it.  A path
with no executable file there stops the suite at once with one line that says where it looked and
what to build, exit 2 (the suites ran their first cases and died in subprocess with a Python
traceback, FileNotFoundError, 2026-11-29)."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def yfdem(suite):
    """The absolute path of $YFDEM (default ./yfdem, relative to ROOT); exit 2 with a message when it
    is not an executable file."""
    given = os.environ.get('YFDEM', './yfdem')
    path = os.path.abspath(os.path.join(ROOT, given))
    if os.path.isfile(path) and os.access(path, os.X_OK):
        return path
    what = 'is not an executable file' if os.path.exists(path) else 'does not exist'
    sys.stderr.write('%s: no yfdem binary: %s %s (YFDEM=%s%s); build it with `make -j2 yfdem` in %s, '
                     'or set YFDEM to a built yfdem\n'
                     % (suite, path, what, given, ', unset: the default' if 'YFDEM' not in os.environ else '',
                        ROOT))
    sys.exit(2)
