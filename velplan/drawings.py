"""``python -m velplan.drawings [--check]``: the command that regenerates (or checks) drawings/.

The work is done by `velplan.sheets.drawings`; this module only keeps the documented command.
"""

import sys

from velplan.sheets.drawings import main

if __name__ == "__main__":
    sys.exit(main())
