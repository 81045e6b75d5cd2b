# pvcheck.py: what the pvpython scripts of tests/paraview share: one line per check, the frame times
# of a reader, and the exit.
import os
import sys

count = {'passed': 0, 'failed': 0}


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    count['passed' if ok else 'failed'] += 1


def times_of(reader):
    """The reader's frame times as a list (ParaView gives a lone frame's time as a number)."""
    tv = reader.TimestepValues
    return [tv] if isinstance(tv, (int, float)) else list(tv or [])


def finish(label):
    print('%s: %d passed, %d failed' % (label, count['passed'], count['failed']))
    sys.stdout.flush()
    os._exit(1 if count['failed'] else 0)  # not sys.exit: ParaView's teardown under Xvfb can print X errors
