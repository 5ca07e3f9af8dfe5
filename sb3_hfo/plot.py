"""``python -m sb3_hfo.plot``: runs :func:`sb3_hfo.cli.plot.main`, the command line it names."""

import sys

from sb3_hfo.cli.plot import main

if __name__ == "__main__":
    sys.exit(main())
