"""``python -m linkage``: the same as the ``linkage`` console script."""

import sys

from linkage.cli import main

sys.exit(main())
