"""``python -m sb3_hfo.evaluate``: runs :func:`sb3_hfo.cli.evaluate.main`, the command line it names."""

import sys

from sb3_hfo.cli.evaluate import main

if __name__ == "__main__":
    sys.exit(main())
