"""``python -m ethasp.interfaces.cli``: the command line, as the ``ethasp`` command."""

import sys

from ethasp.interfaces.cli.execution import main

sys.exit(main())
