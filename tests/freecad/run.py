# The Wrench workbench's tests, run by FreeCAD's own Python:
#
#     freecadcmd tests/freecad/run.py          (make check-freecad)
#
# pytest runs inside freecadcmd (FreeCAD and Part import there, and nowhere
# else); conftest.py starts one wrenchd (build/wrenchd, or $WRENCHD) for the
# session.  $WRENCH_PYTEST_ARGS adds pytest arguments (-k NAME, -x, -v).
# The exit status is pytest's.
import os
import shlex
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
args = ["-q", "-p", "no:cacheprovider", "-rfEs", HERE] + \
    shlex.split(os.environ.get("WRENCH_PYTEST_ARGS", ""))
sys.stdout.flush()
status = pytest.main(args)
sys.stdout.flush()
sys.stderr.flush()
# freecadcmd may catch SystemExit of a script; leave with pytest's status.
os._exit(int(status))
