"""python3 -m scansurf batch INPUT... -o OUT [--workers N] [--option value ...]: scansurf.batch
from the command line (see scansurf.batch_runs)."""

import sys

from .batch_runs import main

sys.exit(main(sys.argv[1:]))
