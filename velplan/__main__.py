import sys

from velplan.cli import main

sys.exit(main())
