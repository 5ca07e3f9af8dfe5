"""``python -m sb3_hfo.enjoy``: runs :func:`sb3_hfo.cli.enjoy.main`, the command line it names."""

import sys

from sb3_hfo.cli.enjoy import main

if __name__ == "__main__":
    sys.exit(main())
