"""``python -m sb3_hfo.train``: runs :func:`sb3_hfo.cli.train.main`, the command line it names."""

import sys

from sb3_hfo.cli.train import main

if __name__ == "__main__":
    sys.exit(main())
