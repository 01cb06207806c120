"""``python -m exudyn_turnout``: the ``exudyn-turnout`` command."""

import sys

from exudyn_turnout.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
