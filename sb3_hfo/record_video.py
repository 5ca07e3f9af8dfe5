"""``python -m sb3_hfo.record_video``: runs :func:`sb3_hfo.cli.record_video.main`, the command line it names."""

import sys

from sb3_hfo.cli.record_video import main

if __name__ == "__main__":
    sys.exit(main())
